// The FAST score kernel on 64-byte vectors (fast_score_vector.inc).
#define ENHANCED_ORB_VECTOR_BYTES 64
#define ENHANCED_ORB_FAST_SCORE_FUNCTION fastScoreRowAvx512
#include "kernels/fast_score_vector.inc"
