// rBRIEF, ORB's descriptor (Rublee et al., ICCV 2011): 256 comparisons of pairs of points of the
// smoothed patch around a keypoint, the pairs rotated by the keypoint's angle. The descriptors are
// bit for bit those of cv::ORB.
#ifndef ENHANCED_ORB_RBRIEF_H
#define ENHANCED_ORB_RBRIEF_H

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "enhanced_orb/rotation_rounding.h"
#include "enhanced_orb/simd.h"

namespace enhanced_orb {

// Descriptor length in bytes (256 bits).
constexpr int kDescriptorBytes = 32;

// One test: bit = I(x1, y1) < I(x2, y2), offsets from the keypoint before rotation.
struct BriefTest {
  int x1, y1, x2, y2;
};

// The 256 tests of cv::ORB (WTA_K 2, patch 31), bit k of byte i being test 8 i + k. They are read
// off the installed OpenCV the first time they are needed (about 50 ms): each test's two points
// are where a single bright or dark pixel, after cv::ORB's smoothing, sets its bit. Throws
// std::runtime_error when what is read off does not reproduce cv::ORB's descriptors.
const std::array<BriefTest, 256>& orbTests();

// The rounding the installed cv::ORB uses, found the first time it is needed (with orbTests()): on
// keypoints whose angles put test points at rounding ties, the one of the five roundings whose
// descriptors equal cv::ORB's. Throws std::runtime_error when none does.
RotationRounding orbRotationRounding();

// What smoothForDescription reuses from call to call.
struct SmoothingBuffers {
  cv::Mat bordered;         // the level (a row with the kernels) with a 3-pixel reflect-101 border
  std::vector<float> rows;  // seven row passes
};

// cv::ORB's smoothing before description, to the bit: a 7x7 Gaussian, sigma 2, of the level as a
// view with a reflect-101 border. At the AVX2 level (x86-64) and the NEON level (aarch64) this
// project's kernels compute it (kernels/pyramid_rows.h) when a check made once finds that they
// reproduce the installed OpenCV's; otherwise cv::GaussianBlur does.
void smoothForDescription(const cv::Mat& level, SmoothingBuffers& buffers, cv::Mat& smoothed);
// Whether smoothForDescription runs this project's kernels at `level` (else cv::GaussianBlur).
bool smoothsWithKernels(SimdLevel level);

// Writes the 32-byte descriptor of each keypoint (level coordinates, integer positions, angle in
// degrees) to rows first_row.. of `descriptors` (CV_8U, 32 columns), reading `smoothed`. Every
// keypoint must lie at least 19 pixels inside the level. The test points rotate as in
// orbRotationRounding(), or as `rounding` says.
void describe(const cv::Mat& smoothed, const std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors, int first_row);
void describe(const cv::Mat& smoothed, const std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors, int first_row,
              RotationRounding rounding);

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_RBRIEF_H
