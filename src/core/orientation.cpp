#include "enhanced_orb/orientation.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include "enhanced_orb/simd.h"
#include "kernels/patch_moments.h"

namespace enhanced_orb {
namespace {

constexpr int kOrientationRadius = kPatchSize / 2;

// Half-widths of the rows of the circular patch: the pixels within r + 1/2 of the centre, a disc
// symmetric under every quarter turn and transposition (the same disc as cv::ORB's).
std::array<int, kOrientationRadius + 1> patchHalfWidths() {
  const double rim = (kOrientationRadius + 0.5) * (kOrientationRadius + 0.5);
  std::array<int, kOrientationRadius + 1> u_max{};
  for (int v = 0; v <= kOrientationRadius; ++v) {
    u_max[v] = static_cast<int>(std::floor(std::sqrt(rim - v * v)));
  }
  return u_max;
}

// The moments' weights over the patch's square: u (for m10) and v (for m01) inside the disc, 0
// outside, so that each row is one fixed-length sum (kernels/patch_moments.h).
struct MomentWeights {
  std::array<std::int8_t, kernels::kMomentRows * kernels::kMomentColumns> u{}, v{};

  MomentWeights() {
    static_assert(kernels::kMomentRows == 2 * kOrientationRadius + 1, "the patch's square");
    const std::array<int, kOrientationRadius + 1> u_max = patchHalfWidths();
    for (int dv = -kOrientationRadius; dv <= kOrientationRadius; ++dv) {
      for (int du = -u_max[std::abs(dv)]; du <= u_max[std::abs(dv)]; ++du) {
        const int at = (dv + kOrientationRadius) * kernels::kMomentColumns + du + kOrientationRadius;
        u[at] = static_cast<std::int8_t>(du);
        v[at] = static_cast<std::int8_t>(dv);
      }
    }
  }
};

}  // namespace

void computeOrientation(const cv::Mat& level, std::vector<cv::KeyPoint>& keypoints) {
  static const MomentWeights weights;
  constexpr int r = kOrientationRadius;
  const cv::Rect inside(r, r, level.cols - 2 * r, level.rows - 2 * r);
  const std::ptrdiff_t step = static_cast<std::ptrdiff_t>(level.step);
  const kernels::PatchMomentsKernel moments = kernels::patchMomentsKernel(activeSimdLevel());
  for (cv::KeyPoint& kp : keypoints) {
    const cv::Point c(cvRound(kp.pt.x), cvRound(kp.pt.y));
    if (!inside.contains(c)) {
      kp.angle = 0.0f;
      continue;
    }
    // Eq 4: moments m_pq = sum x^p y^q I(x, y) over the patch, centred on the keypoint.
    std::int32_t m10 = 0;
    std::int32_t m01 = 0;
    moments(level.ptr<std::uint8_t>(c.y - r) + (c.x - r), step, weights.u.data(), weights.v.data(), &m10, &m01);
    kp.angle = cv::fastAtan2(static_cast<float>(m01), static_cast<float>(m10));  // eqs 5-6
  }
}

}  // namespace enhanced_orb
