// The scalar FAST score: the definition in fast_score.h, written out, and the kernel dispatch.
#include <algorithm>

#include "kernels/dispatch.h"
#include "kernels/fast_score.h"

namespace enhanced_orb {
namespace kernels {

void fastScoreRowScalar(const std::uint8_t* centre, std::ptrdiff_t step, int n, std::uint8_t* out,
                        const std::uint8_t* floors) {
  std::ptrdiff_t offset[16];
  for (int k = 0; k < 16; ++k) {
    offset[k] = kFastCircle[k][1] * step + kFastCircle[k][0];
  }
  for (int x = 0; x < n; ++x) {
    const std::uint8_t* c = centre + x;
    const int v = c[0];
    int score = 0;
    for (int start = 0; start < 16; ++start) {
      int brighter = 255;
      int darker = 255;
      for (int j = 0; j < 9; ++j) {
        const int p = c[offset[(start + j) & 15]];
        brighter = std::min(brighter, p - v);
        darker = std::min(darker, v - p);
      }
      score = std::max({score, brighter, darker});
    }
    out[x] = static_cast<std::uint8_t>(score > floors[x] ? score : 0);
  }
}

FastScoreRowKernel fastScoreRowKernel(SimdLevel level) {
  return selectKernel<FastScoreRowKernel>(level, fastScoreRowScalar, fastScoreRowVector128,
                                          ENHANCED_ORB_X86_KERNEL(fastScoreRowAvx2));
}

void fastScoreRow(SimdLevel level, const std::uint8_t* centre, std::ptrdiff_t step, int n, std::uint8_t* out,
                  const std::uint8_t* floors) {
  fastScoreRowKernel(level)(centre, step, n, out, floors);
}

}  // namespace kernels
}  // namespace enhanced_orb
