// The library's parallel loops: cv::parallel_for_ with the body passed as one pointer, and the
// hand-off between the calling thread and OpenCV's workers made visible to ThreadSanitizer.
#ifndef ENHANCED_ORB_PARALLEL_H
#define ENHANCED_ORB_PARALLEL_H

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

// Runs body(range) over [0, n) in up to n stripes on OpenCV's threads (the caller's among them).
// The lambda handed to cv::parallel_for_ captures one pointer, so the std::function that takes it
// makes no heap allocation. OpenCV's pool (TBB in Debian's build) orders a stripe after the call
// and the call's return after every stripe, but through atomics of its own that ThreadSanitizer
// does not see; in a build with it, the same order is announced here (release before the stripes
// start, acquire as each starts; each releases as it ends, the caller acquires on return), so that
// it checks the bodies themselves.
namespace detail {
// ThreadSanitizer's happens-before annotations; nothing in other builds.
inline void announceRelease(const void* at) {
#ifdef ENHANCED_ORB_TSAN
  __tsan_release(const_cast<void*>(at));
#else
  (void)at;
#endif
}
inline void announceAcquire(const void* at) {
#ifdef ENHANCED_ORB_TSAN
  __tsan_acquire(const_cast<void*>(at));
#else
  (void)at;
#endif
}
}  // namespace detail

template <typename Body>
void parallelFor(int n, const Body& body) {
  const Body* const call = &body;
  detail::announceRelease(call);
  cv::parallel_for_(
      cv::Range(0, n),
      [call](const cv::Range& range) {
        detail::announceAcquire(call);
        (*call)(range);
        detail::announceRelease(call);
      },
      n);
  detail::announceAcquire(call);
}

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_PARALLEL_H
