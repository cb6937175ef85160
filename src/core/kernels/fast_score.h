// The FAST-9 score of every pixel of a row, the kernel behind the score-map corner detector.
//
// For a pixel of value v with the 16 pixels p_0..p_15 of the radius-3 circle (cv::FAST's circle),
// the score is m = max(0, max over the 16 arcs A of 9 contiguous circle pixels of
// max(min_{k in A} (p_k - v), min_{k in A} (v - p_k))). The pixel is a FAST-9 corner at threshold
// t (cv::FAST: 9 contiguous pixels all brighter than v + t or all darker than v - t) exactly when
// m > t, and cv::FAST's corner score is then m - 1, whatever t was.
#ifndef ENHANCED_ORB_KERNELS_FAST_SCORE_H
#define ENHANCED_ORB_KERNELS_FAST_SCORE_H

#include <cstddef>
#include <cstdint>

#include "enhanced_orb/simd.h"

namespace enhanced_orb {
namespace kernels {

// (dx, dy) of the circle pixels, in order around the circle.
constexpr int kFastCircle[16][2] = {{0, 3},  {1, 3},   {2, 2},   {3, 1},   {3, 0},  {3, -1}, {2, -2}, {1, -3},
                                    {0, -3}, {-1, -3}, {-2, -2}, {-3, -1}, {-3, 0}, {-3, 1}, {-2, 2}, {-1, 3}};

// Writes the score of the n pixels centre[0..n) into out[0..n), or 0 where the score is at most
// the pixel's floor, floors[0..n) (no threshold at or above it can make the pixel a corner, nor
// count it in a non-maximum suppression). Every pixel within 3 rows and 3 columns of them must be
// readable; `step` is the row stride in bytes.
void fastScoreRowScalar(const std::uint8_t* centre, std::ptrdiff_t step, int n, std::uint8_t* out,
                        const std::uint8_t* floors);
void fastScoreRowVector128(const std::uint8_t* centre, std::ptrdiff_t step, int n, std::uint8_t* out,
                           const std::uint8_t* floors);
void fastScoreRowAvx2(const std::uint8_t* centre, std::ptrdiff_t step, int n, std::uint8_t* out,
                      const std::uint8_t* floors);

// The kernel of `level` (or the best one below it that this build has); a caller scoring many rows
// picks it once.
using FastScoreRowKernel = void (*)(const std::uint8_t* centre, std::ptrdiff_t step, int n, std::uint8_t* out,
                                    const std::uint8_t* floors);
FastScoreRowKernel fastScoreRowKernel(SimdLevel level);
void fastScoreRow(SimdLevel level, const std::uint8_t* centre, std::ptrdiff_t step, int n, std::uint8_t* out,
                  const std::uint8_t* floors);

}  // namespace kernels
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_KERNELS_FAST_SCORE_H
