#include "enhanced_orb/enhance.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace enhanced_orb {

cv::Mat toGray(const cv::Mat& image, PixelFormat format) {
  struct Expected {
    int type;
    int code;  // cvtColor code, -1 where no colour conversion applies
  };
  Expected e{CV_8UC1, -1};
  switch (format) {
    case PixelFormat::kMono8:
      break;
    case PixelFormat::kMono16:
      e = {CV_16UC1, -1};
      break;
    case PixelFormat::kBGR:
      e = {CV_8UC3, cv::COLOR_BGR2GRAY};
      break;
    case PixelFormat::kRGB:
      e = {CV_8UC3, cv::COLOR_RGB2GRAY};
      break;
    case PixelFormat::kBGRA:
      e = {CV_8UC4, cv::COLOR_BGRA2GRAY};
      break;
    case PixelFormat::kRGBA:
      e = {CV_8UC4, cv::COLOR_RGBA2GRAY};
      break;
  }
  if (image.empty()) {
    return cv::Mat(image.size(), CV_8UC1);
  }
  if (image.type() != e.type) {
    throw std::invalid_argument("toGray: image type " + cv::typeToString(image.type()) +
                                " does not match the format (" + cv::typeToString(e.type) + " expected)");
  }
  if (format == PixelFormat::kMono8) {
    return image;
  }
  cv::Mat gray;
  if (format == PixelFormat::kMono16) {
    image.convertTo(gray, CV_8U, 1.0 / 257.0);
  } else {
    cv::cvtColor(image, gray, e.code);
  }
  return gray;
}

double imageLambda(const cv::Mat& gray) {
  if (gray.empty()) {
    return 0.0;
  }
  cv::Scalar mean, stddev;
  cv::meanStdDev(gray, mean, stddev);
  return stddev[0] / 255.0;  // eq 7 on I/255
}

bool isPoorQuality(double lambda, const EnhanceParams& params) {
  switch (params.gamma_mode) {
    case GammaMode::kAlways:
      return true;
    case GammaMode::kNever:
      return false;
    case GammaMode::kAuto:
      break;
  }
  // Step 3, as the paper states it: poor when lambda exceeds the threshold.
  return lambda > params.std_threshold;
}

GammaLut truncatedGammaLut(const Histogram& histogram, double alpha, double tau) {
  double n = 0.0;
  for (std::uint32_t count : histogram) {
    n += count;
  }
  GammaLut lut{};
  if (n == 0.0) {
    for (int i = 0; i < 256; ++i) {
      lut[i] = static_cast<float>(i);
    }
    return lut;
  }
  // Eq 10: P_i = n_i / n, with its extremes over all 256 levels.
  std::array<double, 256> p{};
  double p_max = 0.0;
  double p_min = 1.0;
  for (int i = 0; i < 256; ++i) {
    p[i] = histogram[i] / n;
    p_max = std::max(p_max, p[i]);
    p_min = std::min(p_min, p[i]);
  }
  // Eq 12: the weighted distribution P_wi = P_max ((P_i - P_min) / (P_max - P_min))^alpha.
  std::array<double, 256> pw{};
  double pw_sum = 0.0;
  for (int i = 0; i < 256; ++i) {
    pw[i] = p_max == p_min ? p_max : p_max * std::pow((p[i] - p_min) / (p_max - p_min), alpha);
    pw_sum += pw[i];
  }
  double cumulative = 0.0;
  for (int i = 0; i < 256; ++i) {
    cumulative += pw[i];
    const double cw = cumulative / pw_sum;                            // eq 13: C_wi
    const double gamma = std::max(tau, 1.0 - cw);                     // eqs 14-15: truncated gamma_i
    lut[i] = static_cast<float>(255.0 * std::pow(i / 255.0, gamma));  // eq 16
  }
  return lut;
}

EnhanceResult enhance(const cv::Mat& gray, const EnhanceParams& params, cv::Mat output) {
  if (!gray.empty() && gray.type() != CV_8UC1) {
    throw std::invalid_argument("enhance: expected CV_8UC1, got " + cv::typeToString(gray.type()));
  }
  const std::vector<std::string> problems = validate(params);
  if (!problems.empty()) {
    throw std::invalid_argument("enhance: " + joinMessages(problems));
  }
  EnhanceResult result;
  if (gray.empty()) {
    result.image.create(gray.size(), CV_8UC1);  // as empty as the input (0 x n or n x 0)
    return result;
  }
  result.lambda = imageLambda(gray);
  result.poor_quality = isPoorQuality(result.lambda, params);

  // Step 4: a bright poor image is enhanced as its negative, and turned back at the end.
  cv::Mat input;
  result.inverted = result.poor_quality && cv::mean(gray)[0] > 128.0;
  if (result.inverted) {
    cv::bitwise_not(gray, input);  // into a new buffer: the caller's image is never written
  } else {
    input = gray;
  }

  // Float buffers are reused from call to call on each thread: fresh ones of this size would be
  // fresh pages from the kernel, whose faults cost more than the arithmetic.
  thread_local struct { cv::Mat input_f, f, e, f_rounded, gamma_f; } scratch;
  cv::Mat& input_f = scratch.input_f;
  cv::Mat& f = scratch.f;
  cv::Mat& e = scratch.e;

  // Eqs 8-9: f = I * h, kept in floating point.
  input.convertTo(input_f, CV_32F);
  cv::GaussianBlur(input_f, f, cv::Size(params.blur_ksize, params.blur_ksize), params.blur_sigma, params.blur_sigma,
                   cv::BORDER_REFLECT_101);

  // Eqs 17-20: G_mask = I - f (eq 18), T_mask = LUT(round f) - f (eq 17) and
  // E = I + sharpening G_mask + beta T_mask (eqs 19-20; T_mask only for poor images), computed as
  // (1 + sharpening) I - (sharpening + beta) f + beta LUT(round f) in vectorised passes.
  const double s = params.sharpening;
  const double b = result.poor_quality ? params.beta : 0.0;
  cv::addWeighted(input_f, 1.0 + s, f, -(s + b), 0.0, e);
  if (result.poor_quality) {
    cv::Mat& f_rounded = scratch.f_rounded;
    f.convertTo(f_rounded, CV_8U);  // round(f), the index into the gamma table
    Histogram histogram{};
    for (int y = 0; y < f_rounded.rows; ++y) {
      const std::uint8_t* row = f_rounded.ptr<std::uint8_t>(y);
      for (int x = 0; x < f_rounded.cols; ++x) {
        ++histogram[row[x]];
      }
    }
    GammaLut lut = truncatedGammaLut(histogram, params.alpha, params.tau);
    cv::Mat& gamma_f = scratch.gamma_f;
    cv::LUT(f_rounded, cv::Mat(1, 256, CV_32F, lut.data()), gamma_f);
    cv::scaleAdd(gamma_f, b, e, e);
  }
  result.image = output;
  e.convertTo(result.image, CV_8U);  // round and saturate; keeps `output`'s buffer when it fits
  if (result.inverted) {
    cv::bitwise_not(result.image, result.image);
  }
  return result;
}

}  // namespace enhanced_orb
