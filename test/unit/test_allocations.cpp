// Allocations per frame of a camera's stream in the default mode (the judgment, the enhancement
// and the extraction), once its workspaces have seen the frames: at most kMaxAllocations for either
// selection. Every operator new of the process and every cv::Mat buffer is counted (the libraries'
// included), as the benchmark counts them (bench/benchmark_extraction.cpp, allocs_per_frame).
#include <gtest/gtest.h>

#include <atomic>
#include <cstdlib>
#include <new>
#include <vector>

#include <opencv2/core.hpp>

#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/orb_extractor.h"
#include "test_images.h"

// (GCC takes the free() of a replaced operator delete for a mismatch.)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
namespace {
std::atomic<long> g_allocations{0};
}  // namespace

void* operator new(std::size_t size) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(size ? size : 1)) {
    return p;
  }
  throw std::bad_alloc();
}
void* operator new[](std::size_t size) {
  return operator new(size);
}
void operator delete(void* p) noexcept {
  std::free(p);
}
void operator delete[](void* p) noexcept {
  std::free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  std::free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  std::free(p);
}

namespace enhanced_orb {
namespace {

// cv::Mat buffers come from cv::fastMalloc, not operator new: counted by wrapping OpenCV's allocator.
class CountingMatAllocator : public cv::MatAllocator {
public:
  cv::UMatData* allocate(int dims, const int* sizes, int type, void* data, size_t* step, cv::AccessFlag flags,
                         cv::UMatUsageFlags usage) const override {
    if (!data) {
      g_allocations.fetch_add(1, std::memory_order_relaxed);
    }
    return base_->allocate(dims, sizes, type, data, step, flags, usage);
  }
  bool allocate(cv::UMatData* data, cv::AccessFlag flags, cv::UMatUsageFlags usage) const override {
    return base_->allocate(data, flags, usage);
  }
  void deallocate(cv::UMatData* data) const override { base_->deallocate(data); }

private:
  cv::MatAllocator* base_ = cv::Mat::getStdAllocator();
};

// cv::ORB::detectAndCompute makes about 290 a frame here.
constexpr double kMaxAllocations = 11.0;

// The frames as one camera's stream, twice: the first pass warms the workspaces (their vectors
// reach the largest size these frames need), the second is counted. Returns the allocations per
// frame of the second pass; `moving` counts its frames judged moving.
double allocationsPerFrame(const std::vector<cv::Mat>& frames, int& moving) {
  static CountingMatAllocator counting;
  cv::MatAllocator* const saved = cv::Mat::getDefaultAllocator();
  cv::Mat::setDefaultAllocator(&counting);
  cv::setNumThreads(1);
  const OrbExtractor extractor;  // the default mode at its 1000 features
  CameraMotion motion;
  ExtractOptions options;
  Extraction out;
  long counted = 0;
  moving = 0;
  for (int pass = 0; pass < 2; ++pass) {
    motion.reset();
    const long before = g_allocations.load();
    for (const cv::Mat& frame : frames) {
      extractor.extract(frame, motion, options, out);
      moving += pass == 1 && options.camera_moving;
    }
    counted = g_allocations.load() - before;
  }
  cv::Mat::setDefaultAllocator(saved);
  return static_cast<double>(counted) / static_cast<double>(frames.size());
}

TEST(Allocations, AStillCamerasFrameMakesAtMostAHandful) {
  const std::vector<cv::Mat> frames = test::cam0Frames(ENHANCED_ORB_EUROC_DIR, 2);
  REQUIRE_SHARED_DATA(!frames.empty(), std::string("frames under ") + ENHANCED_ORB_EUROC_DIR);
  int moving = 0;
  const double per_frame = allocationsPerFrame(frames, moving);
  EXPECT_EQ(moving, 0);  // the still selection throughout
  EXPECT_LE(per_frame, kMaxAllocations);
  EXPECT_GT(per_frame, 0.0);  // the counter counts
  RecordProperty("allocations_per_frame", std::to_string(per_frame));
}

TEST(Allocations, AMovingCamerasFrameMakesAtMostAHandful) {
  const std::vector<cv::Mat> frames = test::cam0Frames(ENHANCED_ORB_MOVING_DIR, 3);
  REQUIRE_SHARED_DATA(!frames.empty(), std::string("frames under ") + ENHANCED_ORB_MOVING_DIR);
  int moving = 0;
  const double per_frame = allocationsPerFrame(frames, moving);
  EXPECT_EQ(moving, static_cast<int>(frames.size()) - 1);  // the moving selection from the second frame
  EXPECT_LE(per_frame, kMaxAllocations);
  EXPECT_GT(per_frame, 0.0);
  RecordProperty("allocations_per_frame", std::to_string(per_frame));
}

}  // namespace
}  // namespace enhanced_orb
