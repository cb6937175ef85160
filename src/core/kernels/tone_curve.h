// The default mode's tone curves applied to a run of pixels that share their four curves (the
// tiles around them), the kernel behind applyTileCurves.
//
// For each pixel, with c = clamp(f, 0, 255), i = min(254, int(c)) and t = c - i, each curve k is
// read as value_k[i] + t slope_k[i]; the four readings r_0..r_3 (tile rows y0, y0, y1, y1 and
// columns x0, x1, x0, x1) are blended as (1 - wy) ((1 - wx) r_0 + wx r_1) + wy ((1 - wx) r_2 +
// wx r_3), each product and sum rounded to float in that order. Output as float, or as 8 bits
// rounded to nearest (ties to even) and saturated, as cv::saturate_cast does.
#ifndef ENHANCED_ORB_KERNELS_TONE_CURVE_H
#define ENHANCED_ORB_KERNELS_TONE_CURVE_H

#include <cstdint>

#include "enhanced_orb/simd.h"

namespace enhanced_orb {
namespace kernels {

struct ToneCurveRun {
  const float* value[4];  // 256 levels each
  const float* slope[4];  // value[i + 1] - value[i]; 0 at 255
  const float* w_left;    // 1 - wx of each pixel of the run
  const float* w_right;   // wx
  float wy_top;           // 1 - wy
  float wy_bottom;        // wy
};

// Exactly one of out8 and out32 is non-null.
void toneCurveRunScalar(const float* f, int n, const ToneCurveRun& run, std::uint8_t* out8, float* out32);
void toneCurveRunAvx2(const float* f, int n, const ToneCurveRun& run, std::uint8_t* out8, float* out32);
void toneCurveRunAvx512(const float* f, int n, const ToneCurveRun& run, std::uint8_t* out8, float* out32);

// The kernel of `level` (or the best one below it that this build has; the 16-byte level has no
// gather, and uses the scalar kernel).
void toneCurveRun(SimdLevel level, const float* f, int n, const ToneCurveRun& run, std::uint8_t* out8, float* out32);

}  // namespace kernels
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_KERNELS_TONE_CURVE_H
