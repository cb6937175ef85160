// A 256-entry table applied to 8-bit pixels: the enhancement's tone curve (enhance.h), which
// cv::LUT applies one byte at a time.
#ifndef ENHANCED_ORB_KERNELS_TABLE_LOOKUP_H
#define ENHANCED_ORB_KERNELS_TABLE_LOOKUP_H

#include <cstdint>

#include "enhanced_orb/simd.h"

namespace enhanced_orb {
namespace kernels {

// out[x] = table[in[x]] for x in [0, n).
void tableLookupScalar(const std::uint8_t* in, int n, const std::uint8_t* table, std::uint8_t* out);
// 32 pixels at a time with AVX2: the table as 16 byte shuffles of 16 entries each.
void tableLookupAvx2(const std::uint8_t* in, int n, const std::uint8_t* table, std::uint8_t* out);

// The kernel of `level`, or the best one below it that this build has.
using TableLookupKernel = void (*)(const std::uint8_t* in, int n, const std::uint8_t* table, std::uint8_t* out);
TableLookupKernel tableLookupKernel(SimdLevel level);

}  // namespace kernels
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_KERNELS_TABLE_LOOKUP_H
