// rBRIEF's rotated test points (rotated_offsets.h) on AVX2 with FMA, eight at a time. Nothing here
// may instantiate an inline function or template shared with other files: the linker keeps one copy
// of such a function for the whole library, possibly this file's, built for an instruction set the
// CPU may not have. A tail shorter than a vector goes to the scalar kernel.
#include <immintrin.h>

#include "kernels/rotated_offsets.h"

namespace enhanced_orb {
namespace kernels {
namespace {

// x a - y b and x b + y a rounded as kX and kY say: each product rounded, or one fused (rbrief.h).
template <Fusion kX>
inline __m256 rotatedX(__m256 x, __m256 y, __m256 a, __m256 b) {
  if constexpr (kX == Fusion::kNone) {
    return _mm256_sub_ps(_mm256_mul_ps(x, a), _mm256_mul_ps(y, b));
  } else if constexpr (kX == Fusion::kFirst) {
    return _mm256_fmsub_ps(x, a, _mm256_mul_ps(y, b));  // fma(x, a, -(y b))
  } else {
    return _mm256_fnmadd_ps(y, b, _mm256_mul_ps(x, a));  // fma(-y, b, x a)
  }
}

template <Fusion kY>
inline __m256 rotatedY(__m256 x, __m256 y, __m256 a, __m256 b) {
  if constexpr (kY == Fusion::kNone) {
    return _mm256_add_ps(_mm256_mul_ps(x, b), _mm256_mul_ps(y, a));
  } else if constexpr (kY == Fusion::kFirst) {
    return _mm256_fmadd_ps(x, b, _mm256_mul_ps(y, a));
  } else {
    return _mm256_fmadd_ps(y, a, _mm256_mul_ps(x, b));
  }
}

template <Fusion kX, Fusion kY>
struct Rotated {
  static void run(const float* x, const float* y, int n, float a, float b, int step, int* offset) {
    const __m256 va = _mm256_set1_ps(a);
    const __m256 vb = _mm256_set1_ps(b);
    const __m256i vstep = _mm256_set1_epi32(step);
    int j = 0;
    for (; j + 8 <= n; j += 8) {
      const __m256 px = _mm256_loadu_ps(x + j);
      const __m256 py = _mm256_loadu_ps(y + j);
      // The conversion rounds by the CPU's mode: nearest, ties to even, as cvRound.
      const __m256i ix = _mm256_cvtps_epi32(rotatedX<kX>(px, py, va, vb));
      const __m256i iy = _mm256_cvtps_epi32(rotatedY<kY>(px, py, va, vb));
      _mm256_storeu_si256(reinterpret_cast<__m256i*>(offset + j), _mm256_add_epi32(_mm256_mullo_epi32(iy, vstep), ix));
    }
    if (j < n) {
      rotatedOffsetsScalar(RotationRounding{kX, kY})(x + j, y + j, n - j, a, b, step, offset + j);
    }
  }
};

}  // namespace

RotatedOffsetsKernel rotatedOffsetsAvx2(RotationRounding rounding) {
  return byRounding<Rotated>(rounding);
}

}  // namespace kernels
}  // namespace enhanced_orb
