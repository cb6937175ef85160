// The FAST score kernel on 32-byte vectors (fast_score_vector.inc).
#define ENHANCED_ORB_VECTOR_BYTES 32
#define ENHANCED_ORB_FAST_SCORE_FUNCTION fastScoreRowAvx2
#include "kernels/fast_score_vector.inc"
