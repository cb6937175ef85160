// The pyramid's row passes, scalar: the definitions in pyramid_rows.h written out, and the dispatch.
#pragma GCC optimize("no-tree-vectorize")
#include <cmath>

#include "kernels/dispatch.h"
#include "kernels/pyramid_rows.h"

namespace enhanced_orb {
namespace kernels {

void linearRowScalar(const std::uint8_t* src, const LinearTaps& taps, std::uint16_t* out) {
  for (int x = 0; x < taps.n; ++x) {
    const std::uint8_t* p = src + taps.index[x];
    const unsigned w = taps.weight[x];
    out[x] = static_cast<std::uint16_t>((256 - w) * p[0] + w * p[1]);
  }
}

void linearColumnScalar(const std::uint16_t* a, const std::uint16_t* b, int weight, int n, std::uint8_t* out) {
  const std::uint32_t w = static_cast<std::uint32_t>(weight);
  for (int x = 0; x < n; ++x) {
    out[x] = static_cast<std::uint8_t>(((256 - w) * a[x] + w * b[x] + 32768u) >> 16);
  }
}

void gaussianRowScalar(const std::uint8_t* src, int n, const float* k, float* out) {
  for (int x = 0; x < n; ++x) {
    float r = k[0] * static_cast<float>(src[x]);
    for (int j = 1; j < 7; ++j) {
      r = std::fma(k[j], static_cast<float>(src[x + j]), r);
    }
    out[x] = r;
  }
}

void gaussianColumnScalar(const float* const* rows, int n, const float* k, std::uint8_t* out) {
  for (int x = 0; x < n; ++x) {
    float c = k[3] * rows[3][x];
    for (int j = 2; j >= 0; --j) {
      c = std::fma(k[j], rows[j][x] + rows[6 - j][x], c);
    }
    const long v = std::lrint(c);  // the default rounding: nearest, ties to even, as cvRound
    out[x] = static_cast<std::uint8_t>(v < 0 ? 0 : v > 255 ? 255 : v);
  }
}

// The 16-byte resize kernels are SSE2 code on x86 (pyramid_rows_vector128.cpp), NEON code on aarch64
// (pyramid_rows_neon.cpp, which has the smoothing's too).
#if defined(__SSE2__) || defined(ENHANCED_ORB_NEON_KERNELS)
#define ENHANCED_ORB_RESIZE128_KERNEL(kernel) kernel
#else
#define ENHANCED_ORB_RESIZE128_KERNEL(kernel) nullptr
#endif

bool hasVectorLinearKernels(SimdLevel level) {
  return selectKernel(level, linearRowScalar, ENHANCED_ORB_RESIZE128_KERNEL(linearRowVector128),
                      ENHANCED_ORB_X86_KERNEL(linearRowAvx2)) != linearRowScalar;
}

void linearRow(SimdLevel level, const std::uint8_t* src, const LinearTaps& taps, std::uint16_t* out) {
  selectKernel(level, linearRowScalar, ENHANCED_ORB_RESIZE128_KERNEL(linearRowVector128),
               ENHANCED_ORB_X86_KERNEL(linearRowAvx2))(src, taps, out);
}

void linearColumn(SimdLevel level, const std::uint16_t* a, const std::uint16_t* b, int weight, int n,
                  std::uint8_t* out) {
  selectKernel(level, linearColumnScalar, ENHANCED_ORB_RESIZE128_KERNEL(linearColumnVector128), nullptr)(a, b, weight,
                                                                                                         n, out);
}

bool hasVectorGaussianKernels(SimdLevel level) {
  return selectKernel(level, gaussianRowScalar, ENHANCED_ORB_NEON_KERNEL(gaussianRowVector128),
                      ENHANCED_ORB_X86_KERNEL(gaussianRowAvx2)) != gaussianRowScalar;
}

void gaussianRow(SimdLevel level, const std::uint8_t* src, int n, const float* k, float* out) {
  selectKernel(level, gaussianRowScalar, ENHANCED_ORB_NEON_KERNEL(gaussianRowVector128),
               ENHANCED_ORB_X86_KERNEL(gaussianRowAvx2))(src, n, k, out);
}

void gaussianColumn(SimdLevel level, const float* const* rows, int n, const float* k, std::uint8_t* out) {
  selectKernel(level, gaussianColumnScalar, ENHANCED_ORB_NEON_KERNEL(gaussianColumnVector128),
               ENHANCED_ORB_X86_KERNEL(gaussianColumnAvx2))(rows, n, k, out);
}

}  // namespace kernels
}  // namespace enhanced_orb
