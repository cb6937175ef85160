// The row passes of the two OpenCV filters the pyramid runs, reproduced to the bit so that they can
// be vectorised for this project's instruction sets (OpenCV's own are built for SSE2 on x86-64, or
// go through its general filter engine): the downscale of cv::resize(INTER_LINEAR_EXACT) and
// cv::ORB's 7x7 Gaussian smoothing before description.
#ifndef ENHANCED_ORB_KERNELS_PYRAMID_ROWS_H
#define ENHANCED_ORB_KERNELS_PYRAMID_ROWS_H

#include <cstdint>

#include "enhanced_orb/simd.h"

namespace enhanced_orb {
namespace kernels {

// cv::resize with INTER_LINEAR_EXACT on 8 bits is separable and exact in integers: two taps per
// output with weights of 8 fractional bits that sum to 256, a row pass to 16 bits and a column
// pass that rounds 16 bits off.
// The kernels read the taps through plain pointers (no container code in a kernel's file).
struct LinearTaps {
  const int* index;             // per output, the first of its two source pixels
  const std::uint16_t* weight;  // of the second one; the first weighs 256 - weight
  int n;                        // outputs
  // For vector kernels: block b < blocks is outputs [8 b, 8 b + 8), whose source pixels lie in the
  // 16 bytes from block_start[b]; block_shuffle[16 b + 2 k + i] is the byte of output 8 b + k's tap i.
  const int* block_start;
  const std::uint8_t* block_shuffle;
  int blocks;
};

// out[x] = (256 - weight[x]) src[index[x]] + weight[x] src[index[x] + 1] for every output x.
void linearRowScalar(const std::uint8_t* src, const LinearTaps& taps, std::uint16_t* out);
void linearRowVector128(const std::uint8_t* src, const LinearTaps& taps, std::uint16_t* out);  // SSE2 or NEON
void linearRowAvx2(const std::uint8_t* src, const LinearTaps& taps, std::uint16_t* out);

// out[x] = ((256 - weight) a[x] + weight b[x] + 2^15) >> 16 for x in [0, n).
void linearColumnScalar(const std::uint16_t* a, const std::uint16_t* b, int weight, int n, std::uint8_t* out);
// SSE2 or NEON; the AVX2 level uses it too (a 32-byte version measured no faster: the pass is a few
// percent of the resize).
void linearColumnVector128(const std::uint16_t* a, const std::uint16_t* b, int weight, int n, std::uint8_t* out);

// cv::ORB smooths each level with cv::GaussianBlur(7x7, sigma 2) of a view into its bordered
// pyramid. OpenCV runs a view through its float filter engine (not the fixed-point path it takes
// for whole images); where it dispatches AVX2 the sums are single-precision fused multiply-adds
// in this order, k being the 7 taps of cv::getGaussianKernel(7, 2, CV_32F):
//   row:    r[x] = k0 s[x], then r[x] = fma(k_j, s[x + j], r[x]) for j = 1..6;
//   column: c = k3 r3[x], then c = fma(k_j, r_j[x] + r_(6-j)[x], c) for j = 2, 1, 0;
//           out[x] = c rounded to the nearest integer (ties to even), saturated to [0, 255].
// The scalar kernels write these steps out (std::fma); rbrief.cpp checks once that the installed
// OpenCV computes them, and otherwise leaves the smoothing to it. The vector kernels need fused
// multiply-add: AVX2 with FMA on x86-64, NEON on aarch64 (no SSE2 ones).
void gaussianRowScalar(const std::uint8_t* src, int n, const float* k, float* out);
void gaussianRowVector128(const std::uint8_t* src, int n, const float* k, float* out);  // NEON only
void gaussianRowAvx2(const std::uint8_t* src, int n, const float* k, float* out);
void gaussianColumnScalar(const float* const* rows, int n, const float* k, std::uint8_t* out);
void gaussianColumnVector128(const float* const* rows, int n, const float* k, std::uint8_t* out);  // NEON only
void gaussianColumnAvx2(const float* const* rows, int n, const float* k, std::uint8_t* out);

// The kernels of `level`, or the best ones below it that this build has. Where only the scalar ones
// would run the pyramid leaves the filter to OpenCV (whose code is faster than this reference):
// the resize has vector kernels at kVector128 (SSE2, NEON) and kAvx2, the smoothing at kVector128 on
// aarch64 (NEON) and at kAvx2.
bool hasVectorLinearKernels(SimdLevel level);
bool hasVectorGaussianKernels(SimdLevel level);
void linearRow(SimdLevel level, const std::uint8_t* src, const LinearTaps& taps, std::uint16_t* out);
void linearColumn(SimdLevel level, const std::uint16_t* a, const std::uint16_t* b, int weight, int n,
                  std::uint8_t* out);
void gaussianRow(SimdLevel level, const std::uint8_t* src, int n, const float* k, float* out);
void gaussianColumn(SimdLevel level, const float* const* rows, int n, const float* k, std::uint8_t* out);

}  // namespace kernels
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_KERNELS_PYRAMID_ROWS_H
