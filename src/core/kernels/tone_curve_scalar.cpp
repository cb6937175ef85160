// The scalar tone-curve kernel: the definition in tone_curve.h, written out, and the dispatch.
#include <algorithm>

#include <opencv2/core.hpp>

#include "kernels/dispatch.h"
#include "kernels/tone_curve.h"

namespace enhanced_orb {
namespace kernels {

void toneCurveRunScalar(const float* f, int n, const ToneCurveRun& run, std::uint8_t* out8, float* out32) {
  for (int x = 0; x < n; ++x) {
    const float c = std::clamp(f[x], 0.0f, 255.0f);
    const int i = std::min(254, static_cast<int>(c));
    const float t = c - static_cast<float>(i);
    float r[4];
    for (int k = 0; k < 4; ++k) {
      r[k] = run.value[k][i] + t * run.slope[k][i];
    }
    const float top = run.w_left[x] * r[0] + run.w_right[x] * r[1];
    const float bottom = run.w_left[x] * r[2] + run.w_right[x] * r[3];
    const float value = run.wy_top * top + run.wy_bottom * bottom;
    if (out32) {
      out32[x] = value;
    } else {
      out8[x] = cv::saturate_cast<std::uint8_t>(value);
    }
  }
}

void toneCurveRun(SimdLevel level, const float* f, int n, const ToneCurveRun& run, std::uint8_t* out8, float* out32) {
  // No 16-byte kernel: SSE2 has no gather.
  selectKernel(level, toneCurveRunScalar, nullptr, ENHANCED_ORB_X86_KERNEL(toneCurveRunAvx2),
               ENHANCED_ORB_X86_KERNEL(toneCurveRunAvx512))(f, n, run, out8, out32);
}

}  // namespace kernels
}  // namespace enhanced_orb
