// Lighting degradations of a frame, for measuring extractors under bad light on real frames.
#ifndef ENHANCED_ORB_EVALUATION_DEGRADE_H
#define ENHANCED_ORB_EVALUATION_DEGRADE_H

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace enhanced_orb {
namespace evaluation {

// A camera in less light: each pixel receives light(x, y) times the light of `gray` (taken as
// linear), collects electrons with shot noise (Poisson, approximated by a Gaussian of variance
// equal to the mean) plus read noise, is amplified by `gain` and quantised to 8 bits.
// `electrons_per_dn`: electrons per digital number at gain 1 (2: a mid-gray pixel of the original
// holds 256 electrons). `light` is CV_32F of gray's size, or empty for a uniform `uniform_light`.
struct SensorModel {
  double electrons_per_dn = 2.0;
  double read_noise_electrons = 3.0;
  double gain = 1.0;
};
cv::Mat lowLight(const cv::Mat& gray, const cv::Mat& light, double uniform_light, const SensorModel& sensor,
                 std::uint64_t seed);

// Light fields: a spotlight (Gaussian fall-off from 1 to `floor`, centred at (0.35 W, 0.4 H), sigma a
// quarter of the diagonal) and a gradient (from `floor` at the left edge to 1 at the right).
cv::Mat spotlightField(cv::Size size, double floor = 0.08);
cv::Mat gradientField(cv::Size size, double floor = 0.08);

// Photometric changes of the paper's Figure 6 and of the EuRoC tests: brightness I' = saturate(I (1 + s)),
// a gamma curve I' = 255 (I / 255)^g, and additive Gaussian noise of `sigma` gray levels (seeded).
cv::Mat changeBrightness(const cv::Mat& gray, double s);
cv::Mat applyGamma(const cv::Mat& gray, double g);
cv::Mat addGaussianNoise(const cv::Mat& gray, double sigma, std::uint64_t seed);

// A named degradation; `apply` is deterministic for a given seed.
struct Degradation {
  std::string name;
  cv::Mat apply(const cv::Mat& gray, std::uint64_t seed) const;
};

// The EuRoC tests: none, lowlight (x0.2, noisy), lowlight_gain (x0.2 then gain x4), night (x0.08
// then gain x4), spotlight,
// gradient, dark (brightness -60 %), bright (+60 %), gamma_0.5, gamma_2, noise_10.
std::vector<Degradation> standardDegradations();

}  // namespace evaluation
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_EVALUATION_DEGRADE_H
