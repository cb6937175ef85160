// The pyramid's row passes (pyramid_rows.h) on AVX2 with FMA. Nothing here may instantiate an
// inline function or template shared with other files: the linker keeps one copy of such a
// function for the whole library, possibly this file's, built for an instruction set the CPU may
// not have. Rows too short for a vector go to the scalar kernels.
#include <immintrin.h>

#include "kernels/pyramid_rows.h"

namespace enhanced_orb {
namespace kernels {

namespace {

// Eight outputs of a row pass: (p0 << 8) + w (p1 - p0) in 16-bit lanes that wrap, which is
// (256 - w) p0 + w p1 exactly since that lies in [0, 65280].
inline __m128i linearBlock(const std::uint8_t* src, const LinearTaps& taps, int b) {
  const __m128i bytes = _mm_loadu_si128(reinterpret_cast<const __m128i*>(src + taps.block_start[b]));
  const __m128i pairs =
      _mm_shuffle_epi8(bytes, _mm_loadu_si128(reinterpret_cast<const __m128i*>(taps.block_shuffle + 16 * b)));
  const __m128i p0 = _mm_and_si128(pairs, _mm_set1_epi16(0xFF));
  const __m128i p1 = _mm_srli_epi16(pairs, 8);
  const __m128i w = _mm_loadu_si128(reinterpret_cast<const __m128i*>(taps.weight + 8 * b));
  return _mm_add_epi16(_mm_slli_epi16(p0, 8), _mm_mullo_epi16(w, _mm_sub_epi16(p1, p0)));
}

}  // namespace

void linearRowAvx2(const std::uint8_t* src, const LinearTaps& taps, std::uint16_t* out) {
  const int blocks = taps.blocks;
  int b = 0;
  for (; b + 2 <= blocks; b += 2) {
    const __m256i r = _mm256_set_m128i(linearBlock(src, taps, b + 1), linearBlock(src, taps, b));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + 8 * b), r);
  }
  for (; b < blocks; ++b) {
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + 8 * b), linearBlock(src, taps, b));
  }
  // The outputs after the vectors, by the scalar kernel.
  const LinearTaps tail{taps.index + 8 * blocks, taps.weight + 8 * blocks, taps.n - (8 * blocks), nullptr, nullptr, 0};
  linearRowScalar(src, tail, out + 8 * blocks);
}

void gaussianRowAvx2(const std::uint8_t* src, int n, const float* k, float* out) {
  if (n < 8) {
    gaussianRowScalar(src, n, k, out);
    return;
  }
  __m256 taps[7];
  for (int j = 0; j < 7; ++j) {
    taps[j] = _mm256_set1_ps(k[j]);
  }
  // In chunks: the chunk's pixels (and the 6 after it) converted to float once, then each output
  // a product and six fused multiply-adds reading them.
  constexpr int kChunk = 256;
  alignas(32) float pixels[kChunk + 16];
  for (int c = 0; c < n; c += kChunk) {
    const int m = n - c < kChunk ? n - c : kChunk;
    const std::uint8_t* s = src + c;
    int i = 0;
    for (; i + 8 <= m + 6; i += 8) {
      _mm256_store_ps(pixels + i, _mm256_cvtepi32_ps(
                                      _mm256_cvtepu8_epi32(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(s + i)))));
    }
    for (; i < m + 6; ++i) {
      pixels[i] = static_cast<float>(s[i]);
    }
    auto block = [&](int x) {
      __m256 r = _mm256_mul_ps(taps[0], _mm256_loadu_ps(pixels + x));
      for (int j = 1; j < 7; ++j) {
        r = _mm256_fmadd_ps(taps[j], _mm256_loadu_ps(pixels + x + j), r);
      }
      _mm256_storeu_ps(out + c + x, r);
    };
    int x = 0;
    for (; x + 8 <= m; x += 8) {
      block(x);
    }
    if (x < m) {
      if (m >= 8) {
        block(m - 8);  // overlapping: rewrites the same values
      } else {
        gaussianRowScalar(s + x, m - x, k, out + c + x);
      }
    }
  }
}

void gaussianColumnAvx2(const float* const* rows, int n, const float* k, std::uint8_t* out) {
  if (n < 16) {
    gaussianColumnScalar(rows, n, k, out);
    return;
  }
  const __m256 k0 = _mm256_set1_ps(k[0]), k1 = _mm256_set1_ps(k[1]), k2 = _mm256_set1_ps(k[2]),
               k3 = _mm256_set1_ps(k[3]);
  auto sums = [&](int x) {
    __m256 c = _mm256_mul_ps(k3, _mm256_loadu_ps(rows[3] + x));
    c = _mm256_fmadd_ps(k2, _mm256_add_ps(_mm256_loadu_ps(rows[2] + x), _mm256_loadu_ps(rows[4] + x)), c);
    c = _mm256_fmadd_ps(k1, _mm256_add_ps(_mm256_loadu_ps(rows[1] + x), _mm256_loadu_ps(rows[5] + x)), c);
    c = _mm256_fmadd_ps(k0, _mm256_add_ps(_mm256_loadu_ps(rows[0] + x), _mm256_loadu_ps(rows[6] + x)), c);
    return _mm256_cvtps_epi32(c);  // the default rounding: nearest, ties to even
  };
  auto block = [&](int x) {
    const __m256i words = _mm256_permute4x64_epi64(_mm256_packs_epi32(sums(x), sums(x + 8)), 0xD8);
    const __m128i bytes = _mm_packus_epi16(_mm256_castsi256_si128(words), _mm256_extracti128_si256(words, 1));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(out + x), bytes);
  };
  int x = 0;
  for (; x + 16 <= n; x += 16) {
    block(x);
  }
  if (x < n) {
    block(n - 16);
  }
}

}  // namespace kernels
}  // namespace enhanced_orb
