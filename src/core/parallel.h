// The library's parallel loops: cv::parallel_for_ with no std::function, and the hand-off between
// the calling thread and OpenCV's workers made visible to ThreadSanitizer.
#ifndef ENHANCED_ORB_PARALLEL_H
#define ENHANCED_ORB_PARALLEL_H

#include <exception>
#include <mutex>

#include <opencv2/core/utility.hpp>

#if defined(__SANITIZE_THREAD__)
#define ENHANCED_ORB_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define ENHANCED_ORB_TSAN 1
#endif
#endif
#ifdef ENHANCED_ORB_TSAN
#include <sanitizer/tsan_interface.h>
#endif

namespace enhanced_orb {

namespace detail {
// ThreadSanitizer's happens-before annotations; nothing in other builds.
#ifdef ENHANCED_ORB_TSAN
inline void announceRelease(const void* at) {
  __tsan_release(const_cast<void*>(at));
}
inline void announceAcquire(const void* at) {
  __tsan_acquire(const_cast<void*>(at));
}
#else
inline void announceRelease(const void*) {}
inline void announceAcquire(const void*) {}
#endif
}  // namespace detail

// Runs body(range) over [0, n) in up to n stripes on OpenCV's threads (the caller's among them),
// through cv::parallel_for_'s ParallelLoopBody overload: no std::function, no heap allocation.
// OpenCV's pool (TBB in Debian's build) orders each stripe after the call, and the call's return
// after every stripe, through atomics of its own that ThreadSanitizer does not see; in a build with
// it, these two orders are announced here (on two addresses, so that no stripe is ordered after
// another), and the sanitizer checks the bodies themselves. An exception a stripe throws reaches
// the caller as it was thrown, after every stripe has ended (of several, one), whatever OpenCV's
// threading backend would do with it.
template <typename Body>
void parallelFor(int n, const Body& body) {
  struct Stripes : cv::ParallelLoopBody {
    explicit Stripes(const Body& b) : body(b) {}
    void operator()(const cv::Range& range) const override {
      detail::announceAcquire(&started);
      try {
        body(range);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        failure = std::current_exception();
      }
      detail::announceRelease(&ended);
    }
    const Body& body;
    mutable std::mutex failure_mutex;
    mutable std::exception_ptr failure;
    const char started = 0, ended = 0;  // the two addresses the order is announced on
  };
  const Stripes stripes(body);
  detail::announceRelease(&stripes.started);
  cv::parallel_for_(cv::Range(0, n), stripes, n);
  detail::announceAcquire(&stripes.ended);
  if (stripes.failure) {
    std::rethrow_exception(stripes.failure);
  }
}

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_PARALLEL_H
