// The first moments of a keypoint's patch (orientation.cpp): weighted sums of its pixels.
#ifndef ENHANCED_ORB_KERNELS_PATCH_MOMENTS_H
#define ENHANCED_ORB_KERNELS_PATCH_MOMENTS_H

#include <cstddef>
#include <cstdint>

#include "enhanced_orb/simd.h"

namespace enhanced_orb {
namespace kernels {

constexpr int kMomentRows = 31;     // the patch's square: 2 x 15 + 1 rows
constexpr int kMomentColumns = 32;  // its 31 columns and a zero weight more, whole vectors

// m10 = sum of u[32 r + i] p_r[i] and m01 = sum of v[32 r + i] p_r[i] over the rows r < 31 and
// columns i < 32, p_r being the row of pixels r step bytes after `corner`. Weights lie in [-15, 15].
using PatchMomentsKernel = void (*)(const std::uint8_t* corner, std::ptrdiff_t step, const std::int8_t* u,
                                    const std::int8_t* v, std::int32_t* m10, std::int32_t* m01);

// The reference, in plain C++ (which the compiler vectorises with the build's baseline instructions).
void patchMomentsScalar(const std::uint8_t* corner, std::ptrdiff_t step, const std::int8_t* u, const std::int8_t* v,
                        std::int32_t* m10, std::int32_t* m01);
// A row of 32 pixels per vector with AVX2: byte products summed in pairs, then in 32 bits.
void patchMomentsAvx2(const std::uint8_t* corner, std::ptrdiff_t step, const std::int8_t* u, const std::int8_t* v,
                      std::int32_t* m10, std::int32_t* m01);

// The kernel of `level`, or the best one below it that this build has.
PatchMomentsKernel patchMomentsKernel(SimdLevel level);

}  // namespace kernels
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_KERNELS_PATCH_MOMENTS_H
