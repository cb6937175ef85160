// The suppression's row loops (suppression_rows.inc), scalar.
// The reference: the same loops, not vectorised.
#pragma GCC optimize("no-tree-vectorize")
#define ENHANCED_ORB_SUPPRESSION_ROW suppressionRowScalar
#define ENHANCED_ORB_SUPPRESSION_KEEP suppressionKeepScalar
#include "kernels/dispatch.h"
#include "kernels/suppression_rows.inc"

namespace enhanced_orb {
namespace kernels {

void suppressionRow(SimdLevel level, ENHANCED_ORB_SUPPRESSION_ROW_ARGS) {
  selectKernel(level, suppressionRowScalar, suppressionRowVector128, ENHANCED_ORB_X86_KERNEL(suppressionRowAvx2))(
      scores, starts, thresholds, cells, b, around);
}

void suppressionKeep(SimdLevel level, ENHANCED_ORB_SUPPRESSION_KEEP_ARGS) {
  selectKernel(level, suppressionKeepScalar, suppressionKeepVector128, ENHANCED_ORB_X86_KERNEL(suppressionKeepAvx2))(
      here, up, down, starts, cells, keep);
}

}  // namespace kernels
}  // namespace enhanced_orb
