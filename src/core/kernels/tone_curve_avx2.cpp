// The tone-curve kernel on 8 pixels at a time with AVX2 gathers; the tail goes to the scalar kernel.
#include <immintrin.h>

// Intrinsics only: no inline function or template shared with other files may be instantiated
// here (fast_score_vector.inc says why).

#include "kernels/tone_curve.h"

namespace enhanced_orb {
namespace kernels {

void toneCurveRunAvx2(const float* f, int n, const ToneCurveRun& run, std::uint8_t* out8, float* out32) {
  const __m256 zero = _mm256_setzero_ps();
  const __m256 top_level = _mm256_set1_ps(255.0f);
  const __m256i last_index = _mm256_set1_epi32(254);
  const __m256 wy_top = _mm256_set1_ps(run.wy_top);
  const __m256 wy_bottom = _mm256_set1_ps(run.wy_bottom);
  int x = 0;
  for (; x + 8 <= n; x += 8) {
    // max then min: clamp for every value a blur of an 8-bit image can take (no NaN).
    const __m256 c = _mm256_min_ps(_mm256_max_ps(_mm256_loadu_ps(f + x), zero), top_level);
    const __m256i i = _mm256_min_epi32(_mm256_cvttps_epi32(c), last_index);
    const __m256 t = _mm256_sub_ps(c, _mm256_cvtepi32_ps(i));
    __m256 r[4];
    for (int k = 0; k < 4; ++k) {
      const __m256 value = _mm256_i32gather_ps(run.value[k], i, 4);
      const __m256 slope = _mm256_i32gather_ps(run.slope[k], i, 4);
      r[k] = _mm256_add_ps(value, _mm256_mul_ps(t, slope));
    }
    const __m256 w_left = _mm256_loadu_ps(run.w_left + x);
    const __m256 w_right = _mm256_loadu_ps(run.w_right + x);
    const __m256 top = _mm256_add_ps(_mm256_mul_ps(w_left, r[0]), _mm256_mul_ps(w_right, r[1]));
    const __m256 bottom = _mm256_add_ps(_mm256_mul_ps(w_left, r[2]), _mm256_mul_ps(w_right, r[3]));
    const __m256 value = _mm256_add_ps(_mm256_mul_ps(wy_top, top), _mm256_mul_ps(wy_bottom, bottom));
    if (out32) {
      _mm256_storeu_ps(out32 + x, value);
    } else {
      // Round to nearest even (the default rounding), then saturate 32 -> 16 -> 8 bits.
      const __m256i rounded = _mm256_cvtps_epi32(value);
      const __m128i words = _mm_packs_epi32(_mm256_castsi256_si128(rounded), _mm256_extracti128_si256(rounded, 1));
      _mm_storel_epi64(reinterpret_cast<__m128i*>(out8 + x), _mm_packus_epi16(words, words));
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
