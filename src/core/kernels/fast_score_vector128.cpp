// The FAST score kernel on 16-byte vectors (fast_score_vector.inc).
#define ENHANCED_ORB_VECTOR_BYTES 16
#define ENHANCED_ORB_FAST_SCORE_FUNCTION fastScoreRowVector128
#include "kernels/fast_score_vector.inc"
