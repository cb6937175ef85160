// rBRIEF's rotated test points (rbrief.h): each point (x, y) turned by the keypoint's angle
// (cosine a, sine b), rounded to the nearest pixel as the installed cv::ORB rounds it
// (RotationRounding), and made an offset from the centre in a row-major image of `step` bytes.
#ifndef ENHANCED_ORB_KERNELS_ROTATED_OFFSETS_H
#define ENHANCED_ORB_KERNELS_ROTATED_OFFSETS_H

#include "enhanced_orb/rotation_rounding.h"
#include "enhanced_orb/simd.h"

namespace enhanced_orb {
namespace kernels {

// offset[j] = round(y'_j) step + round(x'_j) for j in [0, n), where x'_j = x_j a - y_j b and
// y'_j = x_j b + y_j a, each sum rounded as `rounding` says and then rounded to the nearest
// integer, ties to even (cvRound). Points lie within 2^20 of the centre.
using RotatedOffsetsKernel = void (*)(const float* x, const float* y, int n, float a, float b, int step, int* offset);

// The reference, in plain C++ (which the compiler vectorises with the build's baseline instructions).
RotatedOffsetsKernel rotatedOffsetsScalar(RotationRounding rounding);
// Eight points at a time with AVX2 and FMA (x86-64).
RotatedOffsetsKernel rotatedOffsetsAvx2(RotationRounding rounding);

// Kernel<kX, kY>::run, a kernel file's rounding `{kX, kY}`, for `rounding`.
template <template <Fusion, Fusion> class Kernel>
RotatedOffsetsKernel byRounding(RotationRounding rounding) {
  constexpr Fusion kN = Fusion::kNone, kF = Fusion::kFirst, kS = Fusion::kSecond;
  constexpr RotatedOffsetsKernel kByRounding[3][3] = {{Kernel<kN, kN>::run, Kernel<kN, kF>::run, Kernel<kN, kS>::run},
                                                      {Kernel<kF, kN>::run, Kernel<kF, kF>::run, Kernel<kF, kS>::run},
                                                      {Kernel<kS, kN>::run, Kernel<kS, kF>::run, Kernel<kS, kS>::run}};
  return kByRounding[static_cast<int>(rounding.x)][static_cast<int>(rounding.y)];
}

// The kernel of `level`, or the best one below it that this build has.
RotatedOffsetsKernel rotatedOffsetsKernel(SimdLevel level, RotationRounding rounding);

}  // namespace kernels
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_KERNELS_ROTATED_OFFSETS_H
