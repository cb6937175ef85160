// Heap allocations of the whole process, counted: every operator new (the libraries' included) and,
// while a MatBufferCount lives, every cv::Mat buffer. Used by the benchmark (allocs_per_frame) and
// by test_allocations, which link allocation_count.cpp: it replaces the global operator new and
// delete, so at most one translation unit of a program may do so.
#ifndef ENHANCED_ORB_BENCH_ALLOCATION_COUNT_H
#define ENHANCED_ORB_BENCH_ALLOCATION_COUNT_H

#include <opencv2/core.hpp>

namespace enhanced_orb {
namespace bench {

// Allocations counted since the program started.
long allocations();

// While it lives, cv::Mat buffers (cv::fastMalloc, not operator new) count too: OpenCV's default
// allocator is wrapped, and restored when it goes.
class MatBufferCount {
public:
  MatBufferCount();
  ~MatBufferCount();
  MatBufferCount(const MatBufferCount&) = delete;
  MatBufferCount& operator=(const MatBufferCount&) = delete;

private:
  cv::MatAllocator* saved_;
};

}  // namespace bench
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_BENCH_ALLOCATION_COUNT_H
