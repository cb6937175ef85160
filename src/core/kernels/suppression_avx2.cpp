// The suppression's row loops (suppression_rows.inc), avx2.
// The loops vectorised for this file's instruction set.
#define ENHANCED_ORB_SUPPRESSION_ROW suppressionRowAvx2
#define ENHANCED_ORB_SUPPRESSION_KEEP suppressionKeepAvx2
#include "kernels/suppression_rows.inc"
