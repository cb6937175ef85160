// rBRIEF's rotated test points (rotated_offsets.h) in plain C++, and the dispatch.
#include <cmath>

#include "kernels/dispatch.h"
#include "kernels/rotated_offsets.h"

namespace enhanced_orb {
namespace kernels {
namespace {

// Round to nearest, ties to even, as cvRound (the CPU's default rounding) does: adding and
// removing 1.5 * 2^23 leaves a float of magnitude below 2^22 rounded to an integer.
inline float roundToInteger(float x) {
  constexpr float kMagic = 12582912.0f;
  return (x + kMagic) - kMagic;  // not folded: the build neither reassociates nor contracts
}

// x a - y b and x b + y a as `kX` and `kY` round them (std::fma: one rounding; the build contracts
// nothing else).
template <Fusion kX>
inline float rotatedX(float x, float y, float a, float b) {
  if constexpr (kX == Fusion::kNone) {
    return x * a - y * b;
  } else if constexpr (kX == Fusion::kFirst) {
    return std::fma(x, a, -(y * b));
  } else {
    return std::fma(-y, b, x * a);
  }
}

template <Fusion kY>
inline float rotatedY(float x, float y, float a, float b) {
  if constexpr (kY == Fusion::kNone) {
    return x * b + y * a;
  } else if constexpr (kY == Fusion::kFirst) {
    return std::fma(x, b, y * a);
  } else {
    return std::fma(y, a, x * b);
  }
}

template <Fusion kX, Fusion kY>
struct Rotated {
  static void run(const float* x, const float* y, int n, float a, float b, int step, int* offset) {
    for (int j = 0; j < n; ++j) {
      const float ix = roundToInteger(rotatedX<kX>(x[j], y[j], a, b));
      const float iy = roundToInteger(rotatedY<kY>(x[j], y[j], a, b));
      offset[j] = static_cast<int>(iy) * step + static_cast<int>(ix);
    }
  }
};

}  // namespace

RotatedOffsetsKernel rotatedOffsetsScalar(RotationRounding rounding) {
  return byRounding<Rotated>(rounding);
}

RotatedOffsetsKernel rotatedOffsetsKernel(SimdLevel level, RotationRounding rounding) {
  return selectKernel<RotatedOffsetsKernel>(level, rotatedOffsetsScalar(rounding), nullptr,
                                            ENHANCED_ORB_X86_KERNEL(rotatedOffsetsAvx2(rounding)));
}

}  // namespace kernels
}  // namespace enhanced_orb
