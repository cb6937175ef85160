// A 256-entry table applied to 8-bit pixels (table_lookup.h) on AVX2. Nothing here may instantiate
// an inline function or template shared with other files: the linker keeps one copy of such a
// function for the whole library, possibly this file's, built for an instruction set the CPU may
// not have. What is left of a row after its whole vectors goes to the scalar kernel.
#include <immintrin.h>

#include "kernels/table_lookup.h"

namespace enhanced_orb {
namespace kernels {
namespace {

// Entries 16 k .. 16 k + 15 of the table in both 128-bit lanes (the byte shuffle stays in its lane).
struct Slices {
  __m256i slice[16];
  explicit Slices(const std::uint8_t* table) {
    for (int k = 0; k < 16; ++k) {
      slice[k] = _mm256_broadcastsi128_si256(_mm_loadu_si128(reinterpret_cast<const __m128i*>(table + 16 * k)));
    }
  }
};

// table[v] for 32 pixels v. Pixel v - 16 k, raised by 0x70 with saturation, has its sign bit clear
// exactly when v lies in slice k, with v's low four bits: the shuffle then reads slice k's entry,
// and gives 0 elsewhere.
inline __m256i lookup(const Slices& t, __m256i v) {
  const __m256i bias = _mm256_set1_epi8(0x70);
  const __m256i sixteen = _mm256_set1_epi8(16);
  __m256i result = _mm256_setzero_si256();
  __m256i shifted = v;
  for (int k = 0; k < 16; ++k) {
    result = _mm256_or_si256(result, _mm256_shuffle_epi8(t.slice[k], _mm256_adds_epu8(shifted, bias)));
    shifted = _mm256_sub_epi8(shifted, sixteen);
  }
  return result;
}

}  // namespace

void tableLookupAvx2(const std::uint8_t* in, int n, const std::uint8_t* table, std::uint8_t* out) {
  const Slices slices(table);
  int x = 0;
  for (; x + 32 <= n; x += 32) {
    const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(in + x));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + x), lookup(slices, v));
  }
  tableLookupScalar(in + x, n - x, table, out + x);
}

}  // namespace kernels
}  // namespace enhanced_orb
