#include "enhanced_orb/evaluation/degrade.h"

#include <cmath>
#include <stdexcept>

namespace enhanced_orb {
namespace evaluation {

cv::Mat lowLight(const cv::Mat& gray, const cv::Mat& light, double uniform_light, const SensorModel& sensor,
                 std::uint64_t seed) {
  CV_Assert(gray.type() == CV_8UC1 && (light.empty() || (light.type() == CV_32FC1 && light.size() == gray.size())));
  cv::Mat electrons;
  gray.convertTo(electrons, CV_32F, sensor.electrons_per_dn);
  if (light.empty()) {
    electrons *= uniform_light;
  } else {
    electrons = electrons.mul(light);
  }
  cv::RNG rng(seed);
  cv::Mat unit(gray.size(), CV_32F);
  rng.fill(unit, cv::RNG::NORMAL, 0.0, 1.0);
  cv::Mat read(gray.size(), CV_32F);
  rng.fill(read, cv::RNG::NORMAL, 0.0, sensor.read_noise_electrons);
  cv::Mat shot;
  cv::sqrt(electrons, shot);
  const cv::Mat noisy = electrons + shot.mul(unit) + read;
  cv::Mat out;
  noisy.convertTo(out, CV_8U, sensor.gain / sensor.electrons_per_dn);  // round and clip to 8 bits
  return out;
}

cv::Mat spotlightField(cv::Size size, double floor) {
  cv::Mat field(size, CV_32F);
  const double cx = 0.35 * size.width;
  const double cy = 0.4 * size.height;
  const double sigma = 0.25 * std::hypot(size.width, size.height);
  for (int y = 0; y < size.height; ++y) {
    float* row = field.ptr<float>(y);
    for (int x = 0; x < size.width; ++x) {
      const double r2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
      row[x] = static_cast<float>(floor + (1.0 - floor) * std::exp(-r2 / (2.0 * sigma * sigma)));
    }
  }
  return field;
}

cv::Mat gradientField(cv::Size size, double floor) {
  cv::Mat field(size, CV_32F);
  for (int x = 0; x < size.width; ++x) {
    field.col(x).setTo(floor + (1.0 - floor) * x / std::max(1, size.width - 1));
  }
  return field;
}

cv::Mat Degradation::apply(const cv::Mat& gray, std::uint64_t seed) const {
  SensorModel sensor;
  if (name == "none") {
    return gray;
  } else if (name == "lowlight") {
    return lowLight(gray, cv::Mat(), 0.2, sensor, seed);
  } else if (name == "lowlight_gain") {
    sensor.gain = 4.0;
    return lowLight(gray, cv::Mat(), 0.2, sensor, seed);
  } else if (name == "night") {
    sensor.gain = 4.0;
    return lowLight(gray, cv::Mat(), 0.08, sensor, seed);
  } else if (name == "spotlight") {
    return lowLight(gray, spotlightField(gray.size()), 1.0, sensor, seed);
  } else if (name == "gradient") {
    return lowLight(gray, gradientField(gray.size()), 1.0, sensor, seed);
  } else if (name == "dark" || name == "bright") {
    return changeBrightness(gray, name == "dark" ? -0.6 : 0.6);
  } else if (name.rfind("gamma_", 0) == 0) {
    return applyGamma(gray, std::stod(name.substr(6)));
  } else if (name.rfind("noise_", 0) == 0) {
    return addGaussianNoise(gray, std::stod(name.substr(6)), seed);
  }
  throw std::invalid_argument("unknown degradation '" + name + "'");
}

cv::Mat changeBrightness(const cv::Mat& gray, double s) {
  cv::Mat out;
  gray.convertTo(out, CV_8U, 1.0 + s);
  return out;
}

cv::Mat applyGamma(const cv::Mat& gray, double g) {
  cv::Mat lut(1, 256, CV_8U);
  for (int i = 0; i < 256; ++i) {
    lut.at<uchar>(i) = cv::saturate_cast<uchar>(255.0 * std::pow(i / 255.0, g));
  }
  cv::Mat out;
  cv::LUT(gray, lut, out);
  return out;
}

cv::Mat addGaussianNoise(const cv::Mat& gray, double sigma, std::uint64_t seed) {
  cv::Mat noise(gray.size(), CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  cv::Mat g;
  gray.convertTo(g, CV_32F);
  cv::Mat out;
  cv::Mat(g + noise).convertTo(out, CV_8U);
  return out;
}

std::vector<Degradation> standardDegradations() {
  return {{"none"}, {"lowlight"}, {"lowlight_gain"}, {"night"},   {"spotlight"}, {"gradient"},
          {"dark"}, {"bright"},   {"gamma_0.5"},     {"gamma_2"}, {"noise_10"}};
}

}  // namespace evaluation
}  // namespace enhanced_orb
