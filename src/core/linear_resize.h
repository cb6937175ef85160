// cv::resize(src, dst, size, 0, 0, cv::INTER_LINEAR_EXACT) for 8-bit single-channel images, to the
// bit, with this project's row kernels (kernels/pyramid_rows.h). OpenCV's own is built for SSE2 in
// Debian's package and took 0.94 ms for the seven levels of a 752x480 pyramid here; the AVX2
// kernels 0.30 ms, the SSE2 ones 0.42 ms (docs/RESULTS.md, "Speed"). Where this build has no vector
// kernel for the level in use (the scalar level; targets other than x86), and where OpenCV takes
// another path than the bilinear one (a 2x downscale on both axes, which it computes as an area
// average; a source narrower or shorter than 2 pixels; equal sizes), cv::resize itself runs.
#ifndef ENHANCED_ORB_LINEAR_RESIZE_H
#define ENHANCED_ORB_LINEAR_RESIZE_H

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "enhanced_orb/simd.h"

namespace enhanced_orb {

// Keeps the taps of the last pair of sizes and two row buffers: reused from frame to frame, one
// per thread.
class LinearResize {
public:
  void operator()(const cv::Mat& src, cv::Mat& dst, cv::Size size, SimdLevel level);

private:
  struct Axis {
    std::vector<int> index;
    std::vector<std::uint16_t> weight;
  };
  static void taps(int src_length, int dst_length, Axis& axis);
  void plan(cv::Size from, cv::Size to);

  cv::Size from_, to_;
  Axis columns_, rows_;
  std::vector<int> block_start_;
  std::vector<std::uint8_t> block_shuffle_;
  std::vector<std::uint16_t> lines_[2];
};

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_LINEAR_RESIZE_H
