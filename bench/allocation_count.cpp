#include "allocation_count.h"

#include <atomic>
#include <cstdlib>
#include <new>

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
namespace bench {
namespace {

// OpenCV's standard allocator, counting each buffer it allocates (not those given their data).
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

}  // namespace

long allocations() {
  return g_allocations.load();
}

MatBufferCount::MatBufferCount() : saved_(cv::Mat::getDefaultAllocator()) {
  static CountingMatAllocator counting;  // lives as long as any Mat it allocated
  cv::Mat::setDefaultAllocator(&counting);
}

MatBufferCount::~MatBufferCount() {
  cv::Mat::setDefaultAllocator(saved_);
}

}  // namespace bench
}  // namespace enhanced_orb
