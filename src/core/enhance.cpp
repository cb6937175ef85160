#include "enhanced_orb/enhance.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "enhanced_orb/simd.h"
#include "kernels/tone_curve.h"

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
  cv::parallel_for_(
      cv::Range(0, bands),
      [&](const cv::Range& range) {
        for (int k = range.start; k < range.end; ++k) {
          fn(starts[k], starts[k + 1]);
        }
      },
      bands);
}

// The tile row of image row y, in a tiles x tiles grid over `rows` rows.
int tileRow(int y, int tiles, int rows) {
  return std::min(tiles - 1, y * tiles / rows);
}

// Band edges for `bands` bands that each hold whole tile rows (so that each tile's histogram is
// summed by one thread, pixel by pixel in the order of a single pass).
void bandStarts(int rows, int tiles, int bands, std::vector<int>& starts) {
  bands = std::max(1, std::min({bands, tiles, rows}));
  starts.assign(1, 0);
  for (int k = 1; k < bands; ++k) {
    const int first_tile = k * tiles / bands;
    int y = starts.back();
    while (y < rows && tileRow(y, tiles, rows) < first_tile) {
      ++y;
    }
    starts.push_back(y);
  }
  starts.push_back(rows);
}

// Rows [y0, y1) of edgeWeightedHistograms: the weights sqrt(|grad f|) of those rows into `weight`
// (whole-image buffers, the Sobel filters reading f around the band as a whole-image pass does),
// added to the histograms of their tiles.
void addEdgeWeights(const cv::Mat& f, int tiles, int y0, int y1, cv::Mat& gx, cv::Mat& gy, cv::Mat& weight,
                    std::vector<WeightedHistogram>& histograms) {
  const cv::Rect band(0, y0, f.cols, y1 - y0);
  cv::Mat gx_band = gx(band), gy_band = gy(band), weight_band = weight(band);
  cv::Sobel(f(band), gx_band, CV_32F, 1, 0, 3, 1.0, 0.0, cv::BORDER_REFLECT_101);
  cv::Sobel(f(band), gy_band, CV_32F, 0, 1, 3, 1.0, 0.0, cv::BORDER_REFLECT_101);
  cv::magnitude(gx_band, gy_band, weight_band);
  cv::sqrt(weight_band, weight_band);
  // Tile boundaries along x, so that each row is walked tile by tile without a per-pixel lookup.
  int x_end[16];
  for (int x = 0, t = 0; t < tiles; ++t) {
    while (x < f.cols && x * tiles / f.cols == t) {
      ++x;
    }
    x_end[t] = x;
  }
  // The band's tile rows are summed side by side, pixel by pixel, so that their additions (each
  // histogram's own, in the order of a single row-major pass) overlap instead of waiting on each
  // other when neighbouring pixels fall into the same bin.
  int row_start[17];
  int tile_rows = 0;
  for (int y = y0; y < y1; ++y) {
    if (y == y0 || tileRow(y, tiles, f.rows) != tileRow(y - 1, tiles, f.rows)) {
      row_start[tile_rows++] = y;
    }
  }
  row_start[tile_rows] = y1;
  int height = 0;
  for (int k = 0; k < tile_rows; ++k) {
    height = std::max(height, row_start[k + 1] - row_start[k]);
  }
  auto bin = [](float value) {
    // round(f): f >= 0 (a blur of an 8-bit image), rounded half up in double as std::lround does.
    return std::min(255, std::max(0, static_cast<int>(static_cast<double>(value) + 0.5)));
  };
  for (int r = 0; r < height; ++r) {
    const float* fr[16];
    const float* wr[16];
    WeightedHistogram* h[16];  // the tile row's histograms
    int active = 0;
    for (int k = 0; k < tile_rows; ++k) {
      const int y = row_start[k] + r;
      if (y < row_start[k + 1]) {
        fr[active] = f.ptr<float>(y);
        wr[active] = weight.ptr<float>(y);
        h[active] = &histograms[static_cast<size_t>(tileRow(y, tiles, f.rows)) * tiles];
        ++active;
      }
    }
    for (int t = 0, x = 0; t < tiles; ++t) {
      for (; x < x_end[t]; ++x) {
        for (int k = 0; k < active; ++k) {
          h[k][t][bin(fr[k][x])] += wr[k][x];
        }
      }
    }
  }
}

}  // namespace

std::vector<WeightedHistogram> edgeWeightedHistograms(const cv::Mat& f, int tiles) {
  CV_Assert(f.type() == CV_32FC1 && tiles >= 1 && tiles <= 16);
  cv::Mat gx(f.size(), CV_32F), gy(f.size(), CV_32F), weight(f.size(), CV_32F);
  std::vector<WeightedHistogram> histograms(static_cast<size_t>(tiles) * tiles, WeightedHistogram{});
  addEdgeWeights(f, tiles, 0, f.rows, gx, gy, weight, histograms);
  return histograms;
}

namespace {

// Rows [y0, y1) of applyTileCurves into `out` (already of f's size, CV_32F or CV_8U).
void applyTileCurveRows(const cv::Mat& f, const std::vector<GammaLut>& luts, int tiles, cv::Mat& out, int y0, int y1) {
  // Tile centres at (k + 1/2) of a tile; pixels beyond the outer centres use the nearest curves.
  auto neighbours = [tiles](int pos, int length, int& k0, int& k1, float& w1) {
    const float g = (pos + 0.5f) * tiles / length - 0.5f;
    k0 = std::clamp(static_cast<int>(std::floor(g)), 0, tiles - 1);
    k1 = std::min(k0 + 1, tiles - 1);
    w1 = std::clamp(g - static_cast<float>(k0), 0.0f, 1.0f);
  };
  // Each curve as value and slope per level, read at f by linear interpolation. Buffers are kept
  // per thread and reached through plain pointers (a thread_local of a shared library costs a call
  // per access).
  thread_local std::vector<float> curve_buffer;
  thread_local std::vector<int> column_buffer;
  thread_local std::vector<float> weight_buffer;
  curve_buffer.resize(luts.size() * 512);
  column_buffer.resize(2 * static_cast<size_t>(f.cols));
  weight_buffer.resize(2 * static_cast<size_t>(f.cols));
  float* const curves = curve_buffer.data();  // tile t: values at 512 t, slopes at 512 t + 256
  for (size_t t = 0; t < luts.size(); ++t) {
    for (int i = 0; i < 256; ++i) {
      curves[512 * t + i] = luts[t][i];
      curves[512 * t + 256 + i] = i < 255 ? luts[t][i + 1] - luts[t][i] : 0.0f;
    }
  }
  int* const x0 = column_buffer.data();
  int* const x1 = x0 + f.cols;
  float* const w_left = weight_buffer.data();
  float* const w_right = w_left + f.cols;
  for (int x = 0; x < f.cols; ++x) {
    neighbours(x, f.cols, x0[x], x1[x], w_right[x]);
    w_left[x] = 1.0f - w_right[x];
  }
  // Runs of columns between two tile centres share their four curves.
  int run_start[34];
  int runs = 0;
  for (int x = 0; x < f.cols; ++x) {
    if (x == 0 || x0[x] != x0[x - 1] || x1[x] != x1[x - 1]) {
      run_start[runs++] = x;
    }
  }
  run_start[runs] = f.cols;
  const SimdLevel simd = activeSimdLevel();
  const bool to_float = out.depth() == CV_32F;
  for (int y = y0; y < y1; ++y) {
    int ty0 = 0, ty1 = 0;
    float wy = 0.0f;
    neighbours(y, f.rows, ty0, ty1, wy);
    const float* fr = f.ptr<float>(y);
    for (int r = 0; r < runs; ++r) {
      const int x = run_start[r];
      const int end = run_start[r + 1];
      const int tile[4] = {ty0 * tiles + x0[x], ty0 * tiles + x1[x], ty1 * tiles + x0[x], ty1 * tiles + x1[x]};
      kernels::ToneCurveRun run{};
      for (int k = 0; k < 4; ++k) {
        run.value[k] = curves + 512 * tile[k];
        run.slope[k] = curves + 512 * tile[k] + 256;
      }
      run.w_left = w_left + x;
      run.w_right = w_right + x;
      run.wy_top = 1.0f - wy;
      run.wy_bottom = wy;
      kernels::toneCurveRun(simd, fr + x, end - x, run, to_float ? nullptr : out.ptr<std::uint8_t>(y) + x,
                            to_float ? out.ptr<float>(y) + x : nullptr);
    }
  }
}

}  // namespace

void applyTileCurves(const cv::Mat& f, const std::vector<GammaLut>& luts, int tiles, cv::Mat& out, int type) {
  CV_Assert(f.type() == CV_32FC1 && tiles >= 1 && luts.size() == static_cast<size_t>(tiles) * tiles);
  CV_Assert(type == CV_32F || type == CV_8U);
  out.create(f.size(), type);
  applyTileCurveRows(f, luts, tiles, out, 0, f.rows);
}

cv::Mat applyTileCurves(const cv::Mat& f, const std::vector<GammaLut>& luts, int tiles) {
  cv::Mat out;
  applyTileCurves(f, luts, tiles, out, CV_32F);
  return out;
}

EnhanceResult enhance(const cv::Mat& gray, const EnhanceParams& params, cv::Mat output, int threads) {
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
  thread_local struct {
    cv::Mat input_f, f, e, f_rounded, curve_f, gx, gy, weight;
    std::vector<int> starts;
    std::vector<WeightedHistogram> histograms;
    std::vector<GammaLut> luts;
  } scratch;
  // (The lambdas below run on other threads: they must reach these buffers through references,
  // not by the thread_local's name.)
  cv::Mat& input_f = scratch.input_f;
  cv::Mat& f = scratch.f;
  cv::Mat& e = scratch.e;
  cv::Mat& gx = scratch.gx;
  cv::Mat& gy = scratch.gy;
  cv::Mat& weight = scratch.weight;
  input_f.create(gray.size(), CV_32F);
  f.create(gray.size(), CV_32F);

  // With threads > 1 the image is cut into horizontal bands worked on side by side; a filter
  // reads the rows around its band, as a whole-image pass does, so the result is the same.
  const bool equalize = result.poor_quality && params.tone_curve == ToneCurve::kEqualize;
  const int tiles = std::min({params.tone_tiles, gray.cols, gray.rows});
  std::vector<int>& starts = scratch.starts;
  bandStarts(gray.rows, equalize ? tiles : gray.rows, threads, starts);
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
  std::vector<GammaLut>& luts = scratch.luts;
  luts.clear();
  if (equalize) {
    // The default mode's curves, one per tile, read between levels: a dark frame's filtered
    // values carry more than its few integer levels.
    for (cv::Mat* m : {&gx, &gy, &weight}) {
      m->create(gray.size(), CV_32F);
    }
    std::vector<WeightedHistogram>& histograms = scratch.histograms;
    histograms.assign(static_cast<size_t>(tiles) * tiles, WeightedHistogram{});
    forEachBand(starts, [&](int y0, int y1) { addEdgeWeights(f, tiles, y0, y1, gx, gy, weight, histograms); });
    for (const WeightedHistogram& h : histograms) {
      luts.push_back(equalizingLut(h, params.alpha, params.tau));
    }
    if (s == -1.0 && b == 1.0) {
      // E = 0 I - 0 f + LUT(f) = LUT(f) exactly: the curves write the 8-bit image themselves.
      result.image = output;
      result.image.create(gray.size(), CV_8UC1);
      forEachBand(starts, [&](int y0, int y1) { applyTileCurveRows(f, luts, tiles, result.image, y0, y1); });
      return result;
    }
  }
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
  } else if (equalize) {
    cv::Mat& curve_f = scratch.curve_f;
    curve_f.create(gray.size(), CV_32F);
    forEachBand(starts, [&](int y0, int y1) { applyTileCurveRows(f, luts, tiles, curve_f, y0, y1); });
    cv::scaleAdd(curve_f, b, e, e);
  }
  result.image = output;
  e.convertTo(result.image, CV_8U);  // round and saturate; keeps `output`'s buffer when it fits
  if (result.inverted) {
    cv::bitwise_not(result.image, result.image);
  }
  return result;
}

}  // namespace enhanced_orb
