#include "enhanced_orb/enhance.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "enhanced_orb/simd.h"
#include "kernels/table_lookup.h"
#include "parallel.h"

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

ToneLut truncatedGammaLut(const Histogram& histogram, double alpha, double tau) {
  WeightedHistogram counts{};
  std::copy(histogram.begin(), histogram.end(), counts.begin());
  const std::array<double, 256> cw = weightedCdf(counts, alpha);
  const bool empty = cw[255] == 0.0;
  ToneLut lut{};
  for (int i = 0; i < 256; ++i) {
    const double gamma = empty ? 1.0 : std::max(tau, 1.0 - cw[i]);    // eqs 14-15: truncated gamma_i
    lut[i] = static_cast<float>(255.0 * std::pow(i / 255.0, gamma));  // eq 16
  }
  return lut;
}

ToneLut equalizingLut(const WeightedHistogram& histogram, double alpha, double tau) {
  const std::array<double, 256> cw = weightedCdf(histogram, alpha);
  const bool empty = cw[255] == 0.0;
  ToneLut lut{};
  for (int i = 0; i < 256; ++i) {
    lut[i] = static_cast<float>(empty ? i : 255.0 * (tau * i / 255.0 + (1.0 - tau) * cw[i]));
  }
  return lut;
}

ToneLut stretchingLut(const Histogram& histogram, double tau) {
  double n = 0.0;
  for (std::uint32_t count : histogram) {
    n += count;
  }
  // lo: the first level whose count from 0 up to it passes tau n; hi: likewise from 255 down.
  const double clipped = tau * n;
  int lo = 0;
  double below = histogram[0];
  while (lo < 255 && below <= clipped) {
    below += histogram[++lo];
  }
  int hi = 255;
  double above = histogram[255];
  while (hi > 0 && above <= clipped) {
    above += histogram[--hi];
  }
  ToneLut lut{};
  for (int i = 0; i < 256; ++i) {
    lut[i] = hi > lo ? static_cast<float>(std::clamp(255.0 * (i - lo) / (hi - lo), 0.0, 255.0)) : static_cast<float>(i);
  }
  return lut;
}

namespace {

// Runs fn(first_row, end_row) on `bands` horizontal bands of `rows` rows, side by side when there
// are several. Band k starts at starts[k]; starts has bands + 1 entries, the last one `rows`.
template <typename Fn>
void forEachBand(const std::vector<int>& starts, Fn fn) {
  const int bands = static_cast<int>(starts.size()) - 1;
  if (bands <= 1) {
    fn(starts.front(), starts.back());
    return;
  }
  parallelFor(bands, [&](const cv::Range& range) {
    for (int k = range.start; k < range.end; ++k) {
      fn(starts[k], starts[k + 1]);
    }
  });
}

// Band edges for `bands` horizontal bands of about equal height.
void bandStarts(int rows, int bands, std::vector<int>& starts) {
  bands = std::max(1, std::min(bands, rows));
  starts.clear();
  for (int k = 0; k <= bands; ++k) {
    starts.push_back(static_cast<int>(static_cast<long long>(rows) * k / bands));
  }
}

// The plain histogram of an 8-bit image.
Histogram histogramOf(const cv::Mat& image) {
  Histogram histogram{};
  for (int y = 0; y < image.rows; ++y) {
    const std::uint8_t* row = image.ptr<std::uint8_t>(y);
    for (int x = 0; x < image.cols; ++x) {
      ++histogram[row[x]];
    }
  }
  return histogram;
}

// sqrt(g) in 1/64ths for every gradient g = |dx| + |dy| of two 8-bit differences.
const std::array<std::uint32_t, 511>& edgeWeights() {
  static const std::array<std::uint32_t, 511> table = [] {
    std::array<std::uint32_t, 511> t{};
    for (size_t g = 0; g < t.size(); ++g) {
      t[g] = static_cast<std::uint32_t>(std::lround(64.0 * std::sqrt(static_cast<double>(g))));
    }
    return t;
  }();
  return table;
}

// Rows [y0, y1) of edgeWeightedHistogram, added to `counts`. Each even row's gradients are taken a
// run of columns at a time (one plain loop the compiler vectorises, every column, the edges
// clamped apart), then its even columns are summed into two histograms by alternating samples, so
// that neighbouring samples in one bin do not wait on each other; integer sums make the split exact.
void addEdgeWeights(const cv::Mat& f, int y0, int y1, std::array<std::uint64_t, 256>& counts) {
  const std::array<std::uint32_t, 511>& weight = edgeWeights();
  std::array<std::uint64_t, 256> other{};
  const int last_x = f.cols - 1;
  constexpr int kRun = 512;
  std::uint16_t gradient[kRun];
  for (int y = y0 + (y0 & 1); y < y1; y += 2) {
    const std::uint8_t* above = f.ptr<std::uint8_t>(std::max(y - 1, 0));
    const std::uint8_t* row = f.ptr<std::uint8_t>(y);
    const std::uint8_t* below = f.ptr<std::uint8_t>(std::min(y + 1, f.rows - 1));
    // |dx| + |dy| at column x, dx between columns `left` and `right` (x's neighbours, or x itself at an edge).
    auto gradientAt = [&](int x, int left, int right) {
      return static_cast<std::uint16_t>(std::abs(row[right] - row[left]) + std::abs(below[x] - above[x]));
    };
    for (int start = 0; start <= last_x; start += kRun) {  // even: the samples' parity holds
      const int end = std::min(start + kRun, last_x + 1);
      const int from = std::max(start, 1);
      const int to = std::min(end, last_x);  // columns [from, to) have both horizontal neighbours
      for (int x = from; x < to; ++x) {
        gradient[x - start] = gradientAt(x, x - 1, x + 1);
      }
      if (start == 0) {
        gradient[0] = gradientAt(0, 0, std::min(1, last_x));
      }
      if (end == last_x + 1) {
        gradient[last_x - start] = gradientAt(last_x, std::max(last_x - 1, 0), last_x);
      }
      int x = start;
      for (; x + 2 < end; x += 4) {
        counts[row[x]] += weight[gradient[x - start]];
        other[row[x + 2]] += weight[gradient[x + 2 - start]];
      }
      for (; x < end; x += 2) {
        counts[row[x]] += weight[gradient[x - start]];
      }
    }
  }
  for (int i = 0; i < 256; ++i) {
    counts[i] += other[i];
  }
}

// Exact integer counts (weights in 1/64ths) as the histogram equalizingLut reads.
WeightedHistogram toWeightedHistogram(const std::array<std::uint64_t, 256>& counts) {
  WeightedHistogram histogram{};
  for (int i = 0; i < 256; ++i) {
    histogram[i] = static_cast<double>(counts[i]);
  }
  return histogram;
}

// The tone curve of the 8-bit enhancement, from the filtered image f: equalize's (eqs 10-16, the
// edge weights counted per band of `starts`) or stretch's; the identity for an image that is not
// poor.
ToneLut toneCurve8Bit(const cv::Mat& f, const EnhanceParams& params, bool poor_quality, const std::vector<int>& starts,
                      EnhanceWorkspace& scratch) {
  ToneLut curve{};
  if (!poor_quality) {
    for (int i = 0; i < 256; ++i) {
      curve[i] = static_cast<float>(i);
    }
    return curve;
  }
  if (params.tone_curve == ToneCurve::kStretch) {
    return stretchingLut(histogramOf(f), params.tau);
  }
  std::vector<std::array<std::uint64_t, 256>>& counts = scratch.counts;
  counts.assign(starts.size() - 1, {});
  forEachBand(starts, [&](int y0, int y1) {
    const size_t k = static_cast<size_t>(std::lower_bound(starts.begin(), starts.end(), y0) - starts.begin());
    addEdgeWeights(f, y0, y1, counts[k]);
  });
  for (size_t k = 1; k < counts.size(); ++k) {
    for (int i = 0; i < 256; ++i) {
      counts[0][i] += counts[k][i];
    }
  }
  return equalizingLut(toWeightedHistogram(counts[0]), params.alpha, params.tau);
}

// The 8-bit enhancement of tone_curve equalize (the default mode) and stretch: f by OpenCV's
// fixed-point Gaussian, one global curve from f's histogram, and E as one table where sharpening
// is -1.
EnhanceResult enhance8Bit(const cv::Mat& gray, const EnhanceParams& params, cv::Mat output, EnhanceResult result,
                          EnhanceWorkspace& scratch) {
  // Eqs 17-20 with the default mode's curve: E = I + sharpening (I - f) + beta (LUT(f) - f); with
  // sharpening -1 and no curve (beta 0) that is f itself, filtered straight into the result.
  const double s = params.sharpening;
  const double b = result.poor_quality ? params.beta : 0.0;
  result.image = output;
  result.image.create(gray.size(), CV_8UC1);
  const bool f_is_result = s == -1.0 && b == 0.0 && result.image.data != gray.data;
  cv::Mat& f = f_is_result ? result.image : scratch.f8;
  f.create(gray.size(), CV_8UC1);
  std::vector<int>& starts = scratch.starts;
  bandStarts(gray.rows, params.threads, starts);
  // Eqs 8-9: f = I * h, by OpenCV's 8-bit (fixed-point) Gaussian in one pass: a band filtered as a
  // view would round differently along its edges. Nothing beyond a view of a larger image is read.
  cv::GaussianBlur(gray, f, cv::Size(params.blur_ksize, params.blur_ksize), params.blur_sigma, params.blur_sigma,
                   cv::BORDER_REFLECT_101 | cv::BORDER_ISOLATED);
  if (f_is_result) {
    return result;
  }
  const ToneLut curve = toneCurve8Bit(f, params, result.poor_quality, starts, scratch);
  if (s == -1.0) {
    // E = f + beta (LUT(f) - f): one table of f.
    std::uint8_t entries[256];
    for (int i = 0; i < 256; ++i) {
      entries[i] = cv::saturate_cast<std::uint8_t>(i + b * (curve[i] - i));
    }
    const kernels::TableLookupKernel lookup = kernels::tableLookupKernel(activeSimdLevel());
    forEachBand(starts, [&](int y0, int y1) {
      for (int y = y0; y < y1; ++y) {
        lookup(f.ptr<std::uint8_t>(y), f.cols, entries, result.image.ptr<std::uint8_t>(y));
      }
    });
    return result;
  }
  // E = (1 + s) I - s f + beta (LUT(f) - f), per pixel.
  float moved[256];
  for (int i = 0; i < 256; ++i) {
    moved[i] = static_cast<float>(-s * i + b * (curve[i] - i));
  }
  forEachBand(starts, [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y) {
      const std::uint8_t* in = gray.ptr<std::uint8_t>(y);
      const std::uint8_t* fr = f.ptr<std::uint8_t>(y);
      std::uint8_t* out = result.image.ptr<std::uint8_t>(y);
      for (int x = 0; x < gray.cols; ++x) {
        out[x] = cv::saturate_cast<std::uint8_t>(static_cast<float>(1.0 + s) * in[x] + moved[fr[x]]);
      }
    }
  });
  return result;
}

// The paper's method (tone_curve gamma), in floating point, for a non-empty image whose quality
// test is in `result`.
EnhanceResult enhancePaper(const cv::Mat& gray, const EnhanceParams& params, cv::Mat output, EnhanceResult result,
                           EnhanceWorkspace& scratch) {
  // Step 4: a bright poor image is enhanced as its negative, and turned back at the end.
  cv::Mat input;
  result.inverted = result.poor_quality && result.mean_gray > 128.0;
  if (result.inverted) {
    cv::bitwise_not(gray, input);  // into a new buffer: the caller's image is never written
  } else {
    input = gray;
  }

  // The float buffers are the workspace's, reused from call to call.
  cv::Mat& input_f = scratch.input_f;
  cv::Mat& f = scratch.f;
  cv::Mat& e = scratch.e;
  input_f.create(gray.size(), CV_32F);
  f.create(gray.size(), CV_32F);

  // With threads > 1 the image is cut into horizontal bands worked on side by side; a filter
  // reads the rows around its band, as a whole-image pass does, so the result is the same.
  std::vector<int>& starts = scratch.starts;
  bandStarts(gray.rows, params.threads, starts);
  auto band = [&gray](int y0, int y1) { return cv::Rect(0, y0, gray.cols, y1 - y0); };

  // Eqs 8-9: f = I * h, kept in floating point.
  forEachBand(starts, [&](int y0, int y1) {
    cv::Mat dst = input_f(band(y0, y1));
    input(band(y0, y1)).convertTo(dst, CV_32F);
  });
  forEachBand(starts, [&](int y0, int y1) {
    cv::Mat dst = f(band(y0, y1));
    cv::GaussianBlur(input_f(band(y0, y1)), dst, cv::Size(params.blur_ksize, params.blur_ksize), params.blur_sigma,
                     params.blur_sigma, cv::BORDER_REFLECT_101);
  });

  // Eqs 17-20: G_mask = I - f (eq 18), T_mask = LUT(f) - f (eq 17) and
  // E = I + sharpening G_mask + beta T_mask (eqs 19-20; T_mask only for poor images), computed as
  // (1 + sharpening) I - (sharpening + beta) f + beta LUT(f) in vectorised passes.
  const double s = params.sharpening;
  const double b = result.poor_quality ? params.beta : 0.0;
  cv::addWeighted(input_f, 1.0 + s, f, -(s + b), 0.0, e);
  if (result.poor_quality) {
    // The paper's curve reads the table at round(f).
    cv::Mat& f_rounded = scratch.f_rounded;
    f.convertTo(f_rounded, CV_8U);
    ToneLut lut = truncatedGammaLut(histogramOf(f_rounded), params.alpha, params.tau);
    cv::Mat& curve_f = scratch.curve_f;
    cv::LUT(f_rounded, cv::Mat(1, 256, CV_32F, lut.data()), curve_f);
    cv::scaleAdd(curve_f, b, e, e);
  }
  result.image = output;
  e.convertTo(result.image, CV_8U);  // round and saturate; keeps `output`'s buffer when it fits
  if (result.inverted) {
    cv::bitwise_not(result.image, result.image);
  }
  return result;
}

}  // namespace

WeightedHistogram edgeWeightedHistogram(const cv::Mat& f) {
  CV_Assert(f.type() == CV_8UC1);
  std::array<std::uint64_t, 256> counts{};
  if (!f.empty()) {
    addEdgeWeights(f, 0, f.rows, counts);
  }
  return toWeightedHistogram(counts);
}

EnhanceResult enhance(const cv::Mat& gray, const EnhanceParams& params, cv::Mat output) {
  EnhanceWorkspace workspace;
  return enhance(gray, params, workspace, output);
}

EnhanceResult enhance(const cv::Mat& gray, const EnhanceParams& params, EnhanceWorkspace& scratch, cv::Mat output) {
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

  if (params.tone_curve != ToneCurve::kGamma) {
    return enhance8Bit(gray, params, output, result, scratch);
  }
  return enhancePaper(gray, params, output, result, scratch);
}

}  // namespace enhanced_orb
