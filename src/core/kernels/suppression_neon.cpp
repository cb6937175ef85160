// The suppression's row loops (suppression.h) in NEON intrinsics: the 16-byte level on aarch64.
// Each loop runs 16 pixels at a time and leaves the last few of a run to plain code; the
// definitions are suppression_rows.inc's, which the scalar reference builds.
#include <arm_neon.h>

#include "kernels/suppression.h"

namespace enhanced_orb {
namespace kernels {
namespace {

inline std::uint8_t max8(std::uint8_t a, std::uint8_t b) {
  return a > b ? a : b;
}

}  // namespace

void suppressionRowVector128(ENHANCED_ORB_SUPPRESSION_ROW_ARGS) {
  const uint8x16_t one = vdupq_n_u8(1);
  for (int c = 0; c < cells; ++c) {
    const std::uint8_t t = thresholds[c];
    const uint8x16_t vt = vdupq_n_u8(t);
    int i = starts[c];
    const int end = starts[c + 1];
    for (; i + 16 <= end; i += 16) {
      const uint8x16_t m = vld1q_u8(scores + i);
      vst1q_u8(b + i, vandq_u8(vsubq_u8(m, one), vcgtq_u8(m, vt)));  // m - 1 where m > t, else 0
    }
    for (; i < end; ++i) {
      b[i] = scores[i] > t ? static_cast<std::uint8_t>(scores[i] - 1) : 0;
    }
  }
  const int width = starts[cells];
  b[-1] = 0;
  b[width] = 0;
  int i = 0;
  for (; i + 16 <= width; i += 16) {
    vst1q_u8(around + i, vmaxq_u8(vmaxq_u8(vld1q_u8(b + i - 1), vld1q_u8(b + i)), vld1q_u8(b + i + 1)));
  }
  for (; i < width; ++i) {
    around[i] = max8(max8(b[i - 1], b[i]), b[i + 1]);
  }
  for (int c = 1; c < cells; ++c) {  // across a cell edge the neighbour counts 0
    const int right = starts[c];
    around[right - 1] = max8(b[right - 2], b[right - 1]);
    around[right] = max8(b[right], b[right + 1]);
  }
}

void suppressionKeepVector128(ENHANCED_ORB_SUPPRESSION_KEEP_ARGS) {
  const int width = starts[cells];
  const uint8x16_t one = vdupq_n_u8(1);
  int i = 0;
  for (; i + 16 <= width; i += 16) {
    const uint8x16_t neighbours = vmaxq_u8(vmaxq_u8(vld1q_u8(up + i), vld1q_u8(down + i)),
                                           vmaxq_u8(vld1q_u8(here + i - 1), vld1q_u8(here + i + 1)));
    vst1q_u8(keep + i, vandq_u8(vcgtq_u8(vld1q_u8(here + i), neighbours), one));
  }
  for (; i < width; ++i) {
    keep[i] = here[i] > max8(max8(up[i], down[i]), max8(here[i - 1], here[i + 1])) ? 1 : 0;
  }
  for (int c = 1; c < cells; ++c) {  // across a cell edge the horizontal neighbours count 0
    const int right = starts[c];
    const int left = right - 1;
    keep[left] = here[left] > max8(max8(up[left], down[left]), here[left - 1]) ? 1 : 0;
    keep[right] = here[right] > max8(max8(up[right], down[right]), here[right + 1]) ? 1 : 0;
  }
}

}  // namespace kernels
}  // namespace enhanced_orb
