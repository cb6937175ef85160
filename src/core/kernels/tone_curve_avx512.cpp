// The tone-curve kernel on 16 pixels at a time with AVX-512 gathers; the tail goes to the scalar kernel.
#include <immintrin.h>

// Intrinsics only: no inline function or template shared with other files may be instantiated
// here (fast_score_vector.inc says why).

#include "kernels/tone_curve.h"

namespace enhanced_orb {
namespace kernels {

void toneCurveRunAvx512(const float* f, int n, const ToneCurveRun& run, std::uint8_t* out8, float* out32) {
  const __m512 zero = _mm512_setzero_ps();
  const __m512 top_level = _mm512_set1_ps(255.0f);
  const __m512i last_index = _mm512_set1_epi32(254);
  const __m512 wy_top = _mm512_set1_ps(run.wy_top);
  const __m512 wy_bottom = _mm512_set1_ps(run.wy_bottom);
  int x = 0;
  for (; x + 16 <= n; x += 16) {
    const __m512 c = _mm512_min_ps(_mm512_max_ps(_mm512_loadu_ps(f + x), zero), top_level);
    const __m512i i = _mm512_min_epi32(_mm512_cvttps_epi32(c), last_index);
    const __m512 t = _mm512_sub_ps(c, _mm512_cvtepi32_ps(i));
    __m512 r[4];
    for (int k = 0; k < 4; ++k) {
      const __m512 value = _mm512_i32gather_ps(i, run.value[k], 4);
      const __m512 slope = _mm512_i32gather_ps(i, run.slope[k], 4);
      r[k] = _mm512_add_ps(value, _mm512_mul_ps(t, slope));
    }
    const __m512 w_left = _mm512_loadu_ps(run.w_left + x);
    const __m512 w_right = _mm512_loadu_ps(run.w_right + x);
    const __m512 top = _mm512_add_ps(_mm512_mul_ps(w_left, r[0]), _mm512_mul_ps(w_right, r[1]));
    const __m512 bottom = _mm512_add_ps(_mm512_mul_ps(w_left, r[2]), _mm512_mul_ps(w_right, r[3]));
    const __m512 value = _mm512_add_ps(_mm512_mul_ps(wy_top, top), _mm512_mul_ps(wy_bottom, bottom));
    if (out32) {
      _mm512_storeu_ps(out32 + x, value);
    } else {
      // Round to nearest even, then saturate to 0..255 (values are finite).
      const __m512i rounded = _mm512_cvtps_epi32(value);
      _mm_storeu_si128(reinterpret_cast<__m128i*>(out8 + x),
                       _mm512_cvtusepi32_epi8(_mm512_max_epi32(rounded, _mm512_setzero_si512())));
    }
  }
  if (x < n) {
    ToneCurveRun tail = run;
    tail.w_left += x;
    tail.w_right += x;
    toneCurveRunScalar(f + x, n - x, tail, out8 ? out8 + x : nullptr, out32 ? out32 + x : nullptr);
  }
}

}  // namespace kernels
}  // namespace enhanced_orb
