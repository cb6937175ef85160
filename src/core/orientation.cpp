#include "enhanced_orb/orientation.h"

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>

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
// outside, so that each row is one fixed-length loop the compiler vectorises.
struct MomentWeights {
  static constexpr int kSide = 2 * kOrientationRadius + 1;
  static constexpr int kRow = kSide + 1;  // one zero weight more: whole vectors
  std::array<std::array<std::int16_t, kRow>, kSide> u{}, v{};

  MomentWeights() {
    const std::array<int, kOrientationRadius + 1> u_max = patchHalfWidths();
    for (int dv = -kOrientationRadius; dv <= kOrientationRadius; ++dv) {
      for (int du = -u_max[std::abs(dv)]; du <= u_max[std::abs(dv)]; ++du) {
        u[dv + kOrientationRadius][du + kOrientationRadius] = static_cast<std::int16_t>(du);
        v[dv + kOrientationRadius][du + kOrientationRadius] = static_cast<std::int16_t>(dv);
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
  for (cv::KeyPoint& kp : keypoints) {
    const cv::Point c(cvRound(kp.pt.x), cvRound(kp.pt.y));
    if (!inside.contains(c)) {
      kp.angle = 0.0f;
      continue;
    }
    // Eq 4: moments m_pq = sum x^p y^q I(x, y) over the patch, centred on the keypoint.
    const std::uint8_t* corner = level.ptr<std::uint8_t>(c.y - r) + (c.x - r);
    std::int32_t m10 = 0;
    std::int32_t m01 = 0;
    for (int row = 0; row < MomentWeights::kSide; ++row) {
      const std::uint8_t* pixels = corner + row * step;
      const std::int16_t* wu = weights.u[row].data();
      const std::int16_t* wv = weights.v[row].data();
      for (int i = 0; i < MomentWeights::kRow; ++i) {
        const std::int16_t pixel = pixels[i];
        m10 += wu[i] * pixel;  // 16-bit products summed in 32 bits: a multiply-add per pair
        m01 += wv[i] * pixel;
      }
    }
    kp.angle = cv::fastAtan2(static_cast<float>(m01), static_cast<float>(m10));  // eqs 5-6
  }
}

}  // namespace enhanced_orb
