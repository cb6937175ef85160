// The resize's row passes (pyramid_rows.h) on 16-byte SSE2 vectors, for the portable path. Without
// a byte shuffle (SSSE3), each output's two source pixels come in as one 16-bit load. Other
// targets have no such kernels and leave the resize to OpenCV.
#include "kernels/pyramid_rows.h"

#if defined(__SSE2__)
#include <emmintrin.h>

#include <cstring>

namespace enhanced_orb {
namespace kernels {

namespace {

inline int pixelPair(const std::uint8_t* src, int index) {
  std::uint16_t pair;
  std::memcpy(&pair, src + index, sizeof pair);  // src[index] | src[index + 1] << 8
  return pair;
}

}  // namespace

void linearRowVector128(const std::uint8_t* src, const LinearTaps& taps, std::uint16_t* out) {
  const int* index = taps.index;
  int x = 0;
  for (; x + 8 <= taps.n; x += 8) {
    __m128i pairs = _mm_cvtsi32_si128(pixelPair(src, index[x]));
    pairs = _mm_insert_epi16(pairs, pixelPair(src, index[x + 1]), 1);
    pairs = _mm_insert_epi16(pairs, pixelPair(src, index[x + 2]), 2);
    pairs = _mm_insert_epi16(pairs, pixelPair(src, index[x + 3]), 3);
    pairs = _mm_insert_epi16(pairs, pixelPair(src, index[x + 4]), 4);
    pairs = _mm_insert_epi16(pairs, pixelPair(src, index[x + 5]), 5);
    pairs = _mm_insert_epi16(pairs, pixelPair(src, index[x + 6]), 6);
    pairs = _mm_insert_epi16(pairs, pixelPair(src, index[x + 7]), 7);
    // (p0 << 8) + w (p1 - p0) in 16-bit lanes that wrap: (256 - w) p0 + w p1 exactly.
    const __m128i p0 = _mm_and_si128(pairs, _mm_set1_epi16(0xFF));
    const __m128i p1 = _mm_srli_epi16(pairs, 8);
    const __m128i w = _mm_loadu_si128(reinterpret_cast<const __m128i*>(taps.weight + x));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + x),
                     _mm_add_epi16(_mm_slli_epi16(p0, 8), _mm_mullo_epi16(w, _mm_sub_epi16(p1, p0))));
  }
  // The outputs after the vectors, by the scalar kernel.
  const LinearTaps tail{taps.index + x, taps.weight + x, taps.n - x, nullptr, nullptr, 0};
  linearRowScalar(src, tail, out + x);
}

void linearColumnVector128(const std::uint16_t* a, const std::uint16_t* b, int weight, int n, std::uint8_t* out) {
  if (n < 8) {
    linearColumnScalar(a, b, weight, n, out);
    return;
  }
  // As signed 16-bit lanes: (a - 2^15) (256 - w) + (b - 2^15) w = (256 - w) a + w b - 2^23, whose
  // rounded shift is the output less 128.
  const __m128i bias = _mm_set1_epi16(static_cast<short>(0x8000));
  const __m128i weights = _mm_set1_epi32(static_cast<int>((static_cast<unsigned>(weight) << 16) | (256u - weight)));
  const __m128i half = _mm_set1_epi32(32768);
  auto block = [&](int x) {
    const __m128i va = _mm_xor_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(a + x)), bias);
    const __m128i vb = _mm_xor_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(b + x)), bias);
    const __m128i lo = _mm_srai_epi32(_mm_add_epi32(_mm_madd_epi16(_mm_unpacklo_epi16(va, vb), weights), half), 16);
    const __m128i hi = _mm_srai_epi32(_mm_add_epi32(_mm_madd_epi16(_mm_unpackhi_epi16(va, vb), weights), half), 16);
    const __m128i bytes = _mm_packs_epi16(_mm_packs_epi32(lo, hi), _mm_setzero_si128());
    _mm_storel_epi64(reinterpret_cast<__m128i*>(out + x), _mm_xor_si128(bytes, _mm_set1_epi8(static_cast<char>(0x80))));
  };
  int x = 0;
  for (; x + 8 <= n; x += 8) {
    block(x);
  }
  if (x < n) {
    block(n - 8);  // overlapping: rewrites the same values
  }
}

}  // namespace kernels
}  // namespace enhanced_orb

#endif  // __SSE2__
