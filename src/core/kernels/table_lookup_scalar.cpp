// A 256-entry table applied to 8-bit pixels (table_lookup.h), scalar, and the dispatch.
#include "kernels/dispatch.h"
#include "kernels/table_lookup.h"

namespace enhanced_orb {
namespace kernels {

void tableLookupScalar(const std::uint8_t* in, int n, const std::uint8_t* table, std::uint8_t* out) {
  for (int x = 0; x < n; ++x) {
    out[x] = table[in[x]];
  }
}

TableLookupKernel tableLookupKernel(SimdLevel level) {
  return selectKernel<TableLookupKernel>(level, tableLookupScalar, nullptr, ENHANCED_ORB_X86_KERNEL(tableLookupAvx2));
}

}  // namespace kernels
}  // namespace enhanced_orb
