#include "enhanced_orb/enhance.h"

#include <algorithm>
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

double imageLambda(const cv::Mat& gray, double* mean_gray) {
  if (gray.empty()) {
    return 0.0;
  }
  cv::Scalar mean, stddev;
  cv::meanStdDev(gray, mean, stddev);
  if (mean_gray) {
    *mean_gray = mean[0];
  }
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

std::array<double, 256> weightedCdf(const WeightedHistogram& histogram, double alpha) {
  std::array<double, 256> cdf{};
  double n = 0.0;
  for (double count : histogram) {
    n += count;
  }
  if (n <= 0.0) {
    return cdf;
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
    cdf[i] = cumulative / pw_sum;  // eq 13: C_wi
  }
  return cdf;
}

GammaLut truncatedGammaLut(const Histogram& histogram, double alpha, double tau) {
  WeightedHistogram counts{};
  std::copy(histogram.begin(), histogram.end(), counts.begin());
  const std::array<double, 256> cw = weightedCdf(counts, alpha);
  const bool empty = cw[255] == 0.0;
  GammaLut lut{};
  for (int i = 0; i < 256; ++i) {
    const double gamma = empty ? 1.0 : std::max(tau, 1.0 - cw[i]);    // eqs 14-15: truncated gamma_i
    lut[i] = static_cast<float>(255.0 * std::pow(i / 255.0, gamma));  // eq 16
  }
  return lut;
}

GammaLut equalizingLut(const WeightedHistogram& histogram, double alpha, double tau) {
  const std::array<double, 256> cw = weightedCdf(histogram, alpha);
  const bool empty = cw[255] == 0.0;
  GammaLut lut{};
  for (int i = 0; i < 256; ++i) {
    lut[i] = static_cast<float>(empty ? i : 255.0 * (tau * i / 255.0 + (1.0 - tau) * cw[i]));
  }
  return lut;
}

std::vector<WeightedHistogram> edgeWeightedHistograms(const cv::Mat& f, int tiles) {
  CV_Assert(f.type() == CV_32FC1 && tiles >= 1);
  thread_local cv::Mat gx, gy, weight;
  cv::Sobel(f, gx, CV_32F, 1, 0, 3, 1.0, 0.0, cv::BORDER_REFLECT_101);
  cv::Sobel(f, gy, CV_32F, 0, 1, 3, 1.0, 0.0, cv::BORDER_REFLECT_101);
  cv::magnitude(gx, gy, weight);
  cv::sqrt(weight, weight);
  std::vector<WeightedHistogram> histograms(static_cast<size_t>(tiles) * tiles, WeightedHistogram{});
  // Tile boundaries along x, so that each row is walked tile by tile without a per-pixel lookup.
  std::vector<int> x_end(tiles);
  for (int x = 0, t = 0; t < tiles; ++t) {
    while (x < f.cols && x * tiles / f.cols == t) {
      ++x;
    }
    x_end[t] = x;
  }
  for (int y = 0; y < f.rows; ++y) {
    const float* fr = f.ptr<float>(y);
    const float* wr = weight.ptr<float>(y);
    WeightedHistogram* row_tiles = &histograms[static_cast<size_t>(std::min(tiles - 1, y * tiles / f.rows)) * tiles];
    for (int t = 0, x = 0; t < tiles; ++t) {
      WeightedHistogram& h = row_tiles[t];
      for (; x < x_end[t]; ++x) {
        // round(f): f >= 0 (a blur of an 8-bit image), rounded half up in double as std::lround does.
        const int bin = std::min(255, std::max(0, static_cast<int>(static_cast<double>(fr[x]) + 0.5)));
        h[bin] += wr[x];
      }
    }
  }
  return histograms;
}

cv::Mat applyTileCurves(const cv::Mat& f, const std::vector<GammaLut>& luts, int tiles) {
  CV_Assert(f.type() == CV_32FC1 && tiles >= 1 && luts.size() == static_cast<size_t>(tiles) * tiles);
  // Each curve as value and slope per level, read at f by linear interpolation.
  std::vector<std::array<float, 512>> curves(luts.size());
  for (size_t t = 0; t < luts.size(); ++t) {
    for (int i = 0; i < 256; ++i) {
      curves[t][2 * i] = luts[t][i];
      curves[t][2 * i + 1] = i < 255 ? luts[t][i + 1] - luts[t][i] : 0.0f;
    }
  }
  // Tile centres at (k + 1/2) of a tile; pixels beyond the outer centres use the nearest curves.
  auto neighbours = [tiles](int pos, int length, int& k0, int& k1, float& w1) {
    const float g = (pos + 0.5f) * tiles / length - 0.5f;
    k0 = std::clamp(static_cast<int>(std::floor(g)), 0, tiles - 1);
    k1 = std::min(k0 + 1, tiles - 1);
    w1 = std::clamp(g - static_cast<float>(k0), 0.0f, 1.0f);
  };
  std::vector<int> x0(f.cols), x1(f.cols);
  std::vector<float> wx(f.cols);
  for (int x = 0; x < f.cols; ++x) {
    neighbours(x, f.cols, x0[x], x1[x], wx[x]);
  }
  cv::Mat out(f.size(), CV_32F);
  for (int y = 0; y < f.rows; ++y) {
    int y0 = 0, y1 = 0;
    float wy = 0.0f;
    neighbours(y, f.rows, y0, y1, wy);
    const float* fr = f.ptr<float>(y);
    float* o = out.ptr<float>(y);
    const std::array<float, 512>* top_row = &curves[static_cast<size_t>(y0) * tiles];
    const std::array<float, 512>* bottom_row = &curves[static_cast<size_t>(y1) * tiles];
    for (int x = 0; x < f.cols; ++x) {
      // Each curve read at f by linear interpolation between levels: the level and the fraction
      // are the same for the four curves.
      const float c = std::clamp(fr[x], 0.0f, 255.0f);
      const int i = std::min(254, static_cast<int>(c));
      const float frac = c - static_cast<float>(i);
      auto read = [i, frac](const std::array<float, 512>& curve) { return curve[2 * i] + frac * curve[2 * i + 1]; };
      const float top = (1.0f - wx[x]) * read(top_row[x0[x]]) + wx[x] * read(top_row[x1[x]]);
      const float bottom = (1.0f - wx[x]) * read(bottom_row[x0[x]]) + wx[x] * read(bottom_row[x1[x]]);
      o[x] = (1.0f - wy) * top + wy * bottom;
    }
  }
  return out;
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
  result.lambda = imageLambda(gray, &result.mean_gray);
  result.poor_quality = isPoorQuality(result.lambda, params);

  // Step 4: a bright poor image is enhanced as its negative, and turned back at the end. Only the
  // gamma brightens one way; the equalisation treats dark and bright alike.
  const bool gamma_curve = params.tone_curve == ToneCurve::kGamma;
  cv::Mat input;
  result.inverted = gamma_curve && result.poor_quality && result.mean_gray > 128.0;
  if (result.inverted) {
    cv::bitwise_not(gray, input);  // into a new buffer: the caller's image is never written
  } else {
    input = gray;
  }

  // Float buffers are reused from call to call on each thread: fresh ones of this size would be
  // fresh pages from the kernel, whose faults cost more than the arithmetic.
  thread_local struct { cv::Mat input_f, f, e, f_rounded, curve_f; } scratch;
  cv::Mat& input_f = scratch.input_f;
  cv::Mat& f = scratch.f;
  cv::Mat& e = scratch.e;

  // Eqs 8-9: f = I * h, kept in floating point.
  input.convertTo(input_f, CV_32F);
  cv::GaussianBlur(input_f, f, cv::Size(params.blur_ksize, params.blur_ksize), params.blur_sigma, params.blur_sigma,
                   cv::BORDER_REFLECT_101);

  // Eqs 17-20: G_mask = I - f (eq 18), T_mask = LUT(f) - f (eq 17) and
  // E = I + sharpening G_mask + beta T_mask (eqs 19-20; T_mask only for poor images), computed as
  // (1 + sharpening) I - (sharpening + beta) f + beta LUT(f) in vectorised passes.
  const double s = params.sharpening;
  const double b = result.poor_quality ? params.beta : 0.0;
  cv::addWeighted(input_f, 1.0 + s, f, -(s + b), 0.0, e);
  if (result.poor_quality && gamma_curve) {
    // The paper's curve reads the table at round(f).
    cv::Mat& f_rounded = scratch.f_rounded;
    f.convertTo(f_rounded, CV_8U);
    Histogram histogram{};
    for (int y = 0; y < f_rounded.rows; ++y) {
      const std::uint8_t* row = f_rounded.ptr<std::uint8_t>(y);
      for (int x = 0; x < f_rounded.cols; ++x) {
        ++histogram[row[x]];
      }
    }
    GammaLut lut = truncatedGammaLut(histogram, params.alpha, params.tau);
    cv::Mat& curve_f = scratch.curve_f;
    cv::LUT(f_rounded, cv::Mat(1, 256, CV_32F, lut.data()), curve_f);
    cv::scaleAdd(curve_f, b, e, e);
  } else if (result.poor_quality) {
    // The default mode's curve reads the tables between levels: a dark frame's filtered values
    // carry more than its few integer levels.
    const int tiles = std::min({params.tone_tiles, f.cols, f.rows});
    const std::vector<WeightedHistogram> histograms = edgeWeightedHistograms(f, tiles);
    std::vector<GammaLut> luts;
    luts.reserve(histograms.size());
    for (const WeightedHistogram& h : histograms) {
      luts.push_back(equalizingLut(h, params.alpha, params.tau));
    }
    cv::scaleAdd(applyTileCurves(f, luts, tiles), b, e, e);
  }
  result.image = output;
  e.convertTo(result.image, CV_8U);  // round and saturate; keeps `output`'s buffer when it fits
  if (result.inverted) {
    cv::bitwise_not(result.image, result.image);
  }
  return result;
}

}  // namespace enhanced_orb
