// The suppression's row loops (suppression_rows.inc), avx512.
// The loops vectorised for this file's instruction set.
#define ENHANCED_ORB_SUPPRESSION_ROW suppressionRowAvx512
#define ENHANCED_ORB_SUPPRESSION_KEEP suppressionKeepAvx512
#include "kernels/suppression_rows.inc"
