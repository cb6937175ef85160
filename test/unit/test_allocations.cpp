// Allocations per frame of a camera's stream in the default mode (the judgment, the enhancement
// and the extraction), once its workspaces have seen the frames: at most kMaxAllocations for either
// selection. Every operator new of the process and every cv::Mat buffer is counted (the libraries'
// included), as the benchmark counts them (bench/benchmark_extraction.cpp, allocs_per_frame).
#include <gtest/gtest.h>

#include <vector>

#include <opencv2/core.hpp>

#include "allocation_count.h"
#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/orb_extractor.h"
#include "test_images.h"

namespace enhanced_orb {
namespace {

// cv::ORB::detectAndCompute makes about 290 a frame here.
constexpr double kMaxAllocations = 11.0;

// The frames as one camera's stream, twice: the first pass warms the workspaces (their vectors
// reach the largest size these frames need), the second is counted. Returns the allocations per
// frame of the second pass; `moving` counts its frames judged moving.
double allocationsPerFrame(const std::vector<cv::Mat>& frames, int& moving) {
  const bench::MatBufferCount mat_buffers;
  cv::setNumThreads(1);
  const OrbExtractor extractor;  // the default mode at its 1000 features
  CameraMotion motion;
  ExtractOptions options;
  Extraction out;
  long counted = 0;
  moving = 0;
  for (int pass = 0; pass < 2; ++pass) {
    motion.reset();
    const long before = bench::allocations();
    for (const cv::Mat& frame : frames) {
      extractor.extract(frame, motion, options, out);
      moving += pass == 1 && options.camera_moving;
    }
    counted = bench::allocations() - before;
  }
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
