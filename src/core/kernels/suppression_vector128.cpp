// The suppression's row loops (suppression_rows.inc), vector128.
// The loops vectorised for this file's instruction set.
#define ENHANCED_ORB_SUPPRESSION_ROW suppressionRowVector128
#define ENHANCED_ORB_SUPPRESSION_KEEP suppressionKeepVector128
#include "kernels/suppression_rows.inc"
