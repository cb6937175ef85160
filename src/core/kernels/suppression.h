// The row loops of the per-cell non-maximum suppression on a FAST score map (detectCorners).
//
// A band of cells shares its rows; starts[0..cells] are the cells' first columns relative to the
// band's first, then the band's width. For a pixel of score m in a cell of threshold t,
// b = m - 1 when m > t (cv::FAST's corner score) and 0 otherwise; a neighbour across a cell edge
// counts 0. `b`, `around` and the neighbour rows have one readable element before and after the
// row (zero).
#ifndef ENHANCED_ORB_KERNELS_SUPPRESSION_H
#define ENHANCED_ORB_KERNELS_SUPPRESSION_H

#include <cstdint>

#include "enhanced_orb/simd.h"

namespace enhanced_orb {
namespace kernels {

// b of each pixel of a row, and around = the largest b of the pixel and its horizontal neighbours.
#define ENHANCED_ORB_SUPPRESSION_ROW_ARGS                                                                    \
  const std::uint8_t *scores, const int *starts, const std::uint8_t *thresholds, int cells, std::uint8_t *b, \
      std::uint8_t *around
// keep = 1 where b exceeds the b of each of its 8 neighbours (`up` and `down` are the rows above
// and below as `around`), else 0.
#define ENHANCED_ORB_SUPPRESSION_KEEP_ARGS                                                                  \
  const std::uint8_t *here, const std::uint8_t *up, const std::uint8_t *down, const int *starts, int cells, \
      std::uint8_t *keep

void suppressionRowScalar(ENHANCED_ORB_SUPPRESSION_ROW_ARGS);
void suppressionRowVector128(ENHANCED_ORB_SUPPRESSION_ROW_ARGS);
void suppressionRowAvx2(ENHANCED_ORB_SUPPRESSION_ROW_ARGS);
void suppressionKeepScalar(ENHANCED_ORB_SUPPRESSION_KEEP_ARGS);
void suppressionKeepVector128(ENHANCED_ORB_SUPPRESSION_KEEP_ARGS);
void suppressionKeepAvx2(ENHANCED_ORB_SUPPRESSION_KEEP_ARGS);

// The kernels of `level` (or the best ones below it that this build has).
void suppressionRow(SimdLevel level, ENHANCED_ORB_SUPPRESSION_ROW_ARGS);
void suppressionKeep(SimdLevel level, ENHANCED_ORB_SUPPRESSION_KEEP_ARGS);

}  // namespace kernels
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_KERNELS_SUPPRESSION_H
