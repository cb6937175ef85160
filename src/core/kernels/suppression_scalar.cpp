// The suppression's row loops (suppression_rows.inc), scalar.
// The reference: the same loops, not vectorised.
#pragma GCC optimize("no-tree-vectorize")
#define ENHANCED_ORB_SUPPRESSION_ROW suppressionRowScalar
#define ENHANCED_ORB_SUPPRESSION_KEEP suppressionKeepScalar
#include "kernels/suppression_rows.inc"

namespace enhanced_orb {
namespace kernels {

void suppressionRow(SimdLevel level, ENHANCED_ORB_SUPPRESSION_ROW_ARGS) {
  switch (level) {
#if defined(ENHANCED_ORB_X86_KERNELS)
    case SimdLevel::kAvx512:
      return suppressionRowAvx512(scores, starts, thresholds, cells, b, around);
    case SimdLevel::kAvx2:
      return suppressionRowAvx2(scores, starts, thresholds, cells, b, around);
#else
    case SimdLevel::kAvx512:
    case SimdLevel::kAvx2:
#endif
    case SimdLevel::kVector128:
      return suppressionRowVector128(scores, starts, thresholds, cells, b, around);
    case SimdLevel::kScalar:
      break;
  }
  suppressionRowScalar(scores, starts, thresholds, cells, b, around);
}

void suppressionKeep(SimdLevel level, ENHANCED_ORB_SUPPRESSION_KEEP_ARGS) {
  switch (level) {
#if defined(ENHANCED_ORB_X86_KERNELS)
    case SimdLevel::kAvx512:
      return suppressionKeepAvx512(here, up, down, starts, cells, keep);
    case SimdLevel::kAvx2:
      return suppressionKeepAvx2(here, up, down, starts, cells, keep);
#else
    case SimdLevel::kAvx512:
    case SimdLevel::kAvx2:
#endif
    case SimdLevel::kVector128:
      return suppressionKeepVector128(here, up, down, starts, cells, keep);
    case SimdLevel::kScalar:
      break;
  }
  suppressionKeepScalar(here, up, down, starts, cells, keep);
}

}  // namespace kernels
}  // namespace enhanced_orb
