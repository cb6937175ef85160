// The first moments of a keypoint's patch (patch_moments.h) in plain C++, and the dispatch.
#include "kernels/dispatch.h"
#include "kernels/patch_moments.h"

namespace enhanced_orb {
namespace kernels {

void patchMomentsScalar(const std::uint8_t* corner, std::ptrdiff_t step, const std::int8_t* u, const std::int8_t* v,
                        std::int32_t* m10, std::int32_t* m01) {
  std::int32_t sum10 = 0;
  std::int32_t sum01 = 0;
  for (int row = 0; row < kMomentRows; ++row) {
    const std::uint8_t* pixels = corner + row * step;
    const std::int8_t* wu = u + row * kMomentColumns;
    const std::int8_t* wv = v + row * kMomentColumns;
    for (int i = 0; i < kMomentColumns; ++i) {
      const std::int16_t pixel = pixels[i];
      sum10 += wu[i] * pixel;  // 16-bit products summed in 32 bits: a multiply-add per pair
      sum01 += wv[i] * pixel;
    }
  }
  *m10 = sum10;
  *m01 = sum01;
}

PatchMomentsKernel patchMomentsKernel(SimdLevel level) {
  return selectKernel<PatchMomentsKernel>(level, patchMomentsScalar, nullptr,
                                          ENHANCED_ORB_X86_KERNEL(patchMomentsAvx2));
}

}  // namespace kernels
}  // namespace enhanced_orb
