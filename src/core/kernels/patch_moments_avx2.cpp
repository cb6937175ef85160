// The first moments of a keypoint's patch (patch_moments.h) on AVX2. Nothing here may instantiate
// an inline function or template shared with other files: the linker keeps one copy of such a
// function for the whole library, possibly this file's, built for an instruction set the CPU may
// not have.
#include <immintrin.h>

#include "kernels/patch_moments.h"

namespace enhanced_orb {
namespace kernels {
namespace {

inline std::int32_t horizontalSum(__m256i v) {
  __m128i s = _mm_add_epi32(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1));
  s = _mm_add_epi32(s, _mm_shuffle_epi32(s, _MM_SHUFFLE(1, 0, 3, 2)));
  s = _mm_add_epi32(s, _mm_shuffle_epi32(s, _MM_SHUFFLE(2, 3, 0, 1)));
  return _mm_cvtsi128_si32(s);
}

}  // namespace

void patchMomentsAvx2(const std::uint8_t* corner, std::ptrdiff_t step, const std::int8_t* u, const std::int8_t* v,
                      std::int32_t* m10, std::int32_t* m01) {
  const __m256i ones = _mm256_set1_epi16(1);
  __m256i sum10 = _mm256_setzero_si256();
  __m256i sum01 = _mm256_setzero_si256();
  for (int row = 0; row < kMomentRows; ++row) {
    const __m256i pixels = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(corner + row * step));
    const __m256i wu = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(u + row * kMomentColumns));
    const __m256i wv = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(v + row * kMomentColumns));
    // Two products of a pixel (at most 255) and a weight (at most 15 either way) fit 16 bits: the
    // pairwise sums never saturate.
    sum10 = _mm256_add_epi32(sum10, _mm256_madd_epi16(_mm256_maddubs_epi16(pixels, wu), ones));
    sum01 = _mm256_add_epi32(sum01, _mm256_madd_epi16(_mm256_maddubs_epi16(pixels, wv), ones));
  }
  *m10 = horizontalSum(sum10);
  *m01 = horizontalSum(sum01);
}

}  // namespace kernels
}  // namespace enhanced_orb
