// A straightforward implementation of the whole extraction, written from docs/ALGORITHM.md with
// OpenCV's building blocks and no call into the library's stages (it uses the library's types
// only): the enhancement pixel by pixel (default mode and stretch) or as separate passes over float
// images (paper), the curves of eqs 10-16, the grid and the thresholds of eqs 21-34 through
// cv::threshold, cv::FAST run cell by cell, the budget's shares and the spread selection on
// cv::KeyPoint vectors, the orientation pixel by pixel, and cv::ORB::compute level by level. The
// library's extractor must give exactly its enhanced image, keypoints, thresholds and descriptors.
#ifndef ENHANCED_ORB_TEST_REFERENCE_EXTRACTOR_H
#define ENHANCED_ORB_TEST_REFERENCE_EXTRACTOR_H

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/adaptive_threshold.h"
#include "enhanced_orb/enhance.h"
#include "enhanced_orb/orb_extractor.h"

namespace enhanced_orb {
namespace reference {

// Eqs 10-13 as ALGORITHM.md writes them: P_i = n_i / n, P_wi = P_max ((P_i - P_min) /
// (P_max - P_min))^alpha (P_max where every level is as frequent), C_wi = sum_{h <= i} P_wh / sum P_wh;
// all zero for an empty histogram.
template <typename Counts>
std::vector<double> weightedCumulative(const Counts& counts, double alpha) {
  const double n = std::accumulate(counts.begin(), counts.end(), 0.0);
  std::vector<double> c(256, 0.0);
  if (n <= 0.0) {
    return c;
  }
  std::vector<double> p(256), pw(256);
  std::transform(counts.begin(), counts.end(), p.begin(), [n](double count) { return count / n; });
  const auto [least, most] = std::minmax_element(p.begin(), p.end());
  const double p_min = *least, p_max = *most;
  std::transform(p.begin(), p.end(), pw.begin(), [&](double pi) {
    return p_max == p_min ? p_max : p_max * std::pow((pi - p_min) / (p_max - p_min), alpha);
  });
  std::partial_sum(pw.begin(), pw.end(), c.begin());
  const double total = c.back();
  std::for_each(c.begin(), c.end(), [total](double& v) { v /= total; });
  return c;
}

// The curve LUT(i) = value(i, C_w(i)) of a histogram; the identity for an empty one.
template <typename Counts, typename Value>
ToneLut curveOf(const Counts& counts, double alpha, Value value) {
  const std::vector<double> c = weightedCumulative(counts, alpha);
  ToneLut curve{};
  for (int i = 0; i < 256; ++i) {
    curve[i] = static_cast<float>(c.back() == 0.0 ? i : value(i, c[i]));
  }
  return curve;
}

// The default mode's curve: LUT(i) = 255 (tau i / 255 + (1 - tau) C_w(i)).
template <typename Counts>
ToneLut equalizingCurve(const Counts& counts, double alpha, double tau) {
  return curveOf(counts, alpha, [tau](int i, double c) { return 255.0 * (tau * i / 255.0 + (1.0 - tau) * c); });
}

// The paper's curve, eqs 14-16: gamma_i = max(tau, 1 - C_wi), LUT(i) = 255 (i / 255)^gamma_i.
template <typename Counts>
ToneLut gammaCurve(const Counts& counts, double alpha, double tau) {
  return curveOf(counts, alpha, [tau](int i, double c) { return 255.0 * std::pow(i / 255.0, std::max(tau, 1.0 - c)); });
}

// tone_curve stretch as ALGORITHM.md defines it: lo is the lowest level with more than tau n of
// the n pixels of f at or below it, hi the highest with more than tau n at or above it;
// LUT(i) = 255 (i - lo) / (hi - lo) clipped to [0, 255], the identity when hi <= lo.
inline ToneLut stretchCurve(const cv::Mat& f, double tau) {
  std::vector<std::uint8_t> sorted(f.begin<std::uint8_t>(), f.end<std::uint8_t>());
  std::sort(sorted.begin(), sorted.end());
  const double n = static_cast<double>(sorted.size());
  auto atOrBelow = [&](int level) {
    return static_cast<double>(std::upper_bound(sorted.begin(), sorted.end(), level) - sorted.begin());
  };
  int lo = 0;
  while (lo < 255 && !(atOrBelow(lo) > tau * n)) {
    ++lo;
  }
  int hi = 255;
  while (hi > 0 && !(n - atOrBelow(hi - 1) > tau * n)) {
    --hi;
  }
  ToneLut curve{};
  for (int i = 0; i < 256; ++i) {
    curve[i] = hi > lo ? static_cast<float>(std::min(255.0, std::max(0.0, 255.0 * (i - lo) / (hi - lo))))
                       : static_cast<float>(i);
  }
  return curve;
}

// The default mode's enhancement written out: OpenCV's 8-bit Gaussian, the edge-weighted
// histogram summed sample by sample (or the stretch curve), E computed pixel by pixel.
inline EnhanceResult enhanceEqualize(const cv::Mat& gray, const EnhanceParams& params, EnhanceResult result) {
  cv::Mat f;
  cv::GaussianBlur(gray, f, cv::Size(params.blur_ksize, params.blur_ksize), params.blur_sigma, params.blur_sigma,
                   cv::BORDER_REFLECT_101 | cv::BORDER_ISOLATED);
  ToneLut curve{};
  for (int i = 0; i < 256; ++i) {
    curve[i] = static_cast<float>(i);
  }
  if (result.poor_quality) {
    WeightedHistogram histogram{};
    auto at = [&f](int x, int y) {
      return static_cast<int>(f.at<std::uint8_t>(std::clamp(y, 0, f.rows - 1), std::clamp(x, 0, f.cols - 1)));
    };
    for (int y = 0; y < f.rows; y += 2) {
      for (int x = 0; x < f.cols; x += 2) {
        const int g = std::abs(at(x + 1, y) - at(x - 1, y)) + std::abs(at(x, y + 1) - at(x, y - 1));
        histogram[at(x, y)] += std::round(64.0 * std::sqrt(static_cast<double>(g)));
      }
    }
    curve = params.tone_curve == ToneCurve::kStretch ? stretchCurve(f, params.tau)
                                                     : equalizingCurve(histogram, params.alpha, params.tau);
  }
  const double s = params.sharpening;
  const double b = result.poor_quality ? params.beta : 0.0;
  result.image.create(gray.size(), CV_8UC1);
  for (int y = 0; y < gray.rows; ++y) {
    for (int x = 0; x < gray.cols; ++x) {
      const int v = f.at<std::uint8_t>(y, x);
      const int i = gray.at<std::uint8_t>(y, x);
      std::uint8_t& out = result.image.at<std::uint8_t>(y, x);
      if (s == -1.0) {
        out = cv::saturate_cast<std::uint8_t>(v + b * (curve[v] - v));  // f + beta (LUT(f) - f)
      } else {
        const float moved = static_cast<float>(-s * v + b * (curve[v] - v));
        out = cv::saturate_cast<std::uint8_t>(static_cast<float>(1.0 + s) * i + moved);
      }
    }
  }
  return result;
}

// Steps 1-3 and the tone curve's output (eqs 7-20) for valid parameters: lambda = std(I / 255)
// (eq 7), poor when it exceeds std_threshold (gamma_mode auto), always or never otherwise.
inline EnhanceResult enhance(const cv::Mat& gray, const EnhanceParams& params) {
  EnhanceResult result;
  result.image = cv::Mat(gray.size(), CV_8UC1);
  if (gray.empty()) {
    return result;
  }
  cv::Scalar mean, deviation;
  cv::meanStdDev(gray, mean, deviation);
  result.mean_gray = mean[0];
  result.lambda = deviation[0] / 255.0;
  result.poor_quality = params.gamma_mode == GammaMode::kAlways ||
                        (params.gamma_mode == GammaMode::kAuto && result.lambda > params.std_threshold);
  cv::Mat output;

  if (params.tone_curve != ToneCurve::kGamma) {  // equalize (the default mode) or stretch
    return enhanceEqualize(gray, params, result);
  }

  // The paper's method. Step 4: a bright poor image is enhanced as its negative, and turned back
  // at the end.
  cv::Mat input;
  result.inverted = result.poor_quality && result.mean_gray > 128.0;
  if (result.inverted) {
    cv::bitwise_not(gray, input);
  } else {
    input = gray;
  }

  struct {
    cv::Mat input_f, f, e, f_rounded, curve_f;
  } scratch;
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
  if (result.poor_quality) {
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
    ToneLut lut = gammaCurve(histogram, params.alpha, params.tau);
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

// The grid of ALGORITHM.md: cell (cx, cy) of an m x m grid spans columns
// [round(cx W / m), round((cx + 1) W / m)) and rows likewise.
inline cv::Rect cell(cv::Size size, int m, int cx, int cy) {
  const auto edge = [m](int length, int k) { return static_cast<int>(std::lround(double(k) * length / m)); };
  return cv::Rect(cv::Point(edge(size.width, cx), edge(size.height, cy)),
                  cv::Point(edge(size.width, cx + 1), edge(size.height, cy + 1)));
}

inline std::vector<cv::KeyPoint> detectCorners(const cv::Mat& level, const cv::Mat& thresholds) {
  constexpr int kFastRadius = 3;
  std::vector<cv::KeyPoint> corners;
  const cv::Rect interior(kEdgeThreshold, kEdgeThreshold, level.cols - 2 * kEdgeThreshold,
                          level.rows - 2 * kEdgeThreshold);
  if (interior.width <= 0 || interior.height <= 0) {
    return corners;
  }
  const int grid = thresholds.rows;
  std::vector<cv::KeyPoint> found;
  for (int cy = 0; cy < grid; ++cy) {
    for (int cx = 0; cx < grid; ++cx) {
      const cv::Rect area = reference::cell(level.size(), grid, cx, cy) & interior;
      if (area.empty()) {
        continue;
      }
      const cv::Rect window(area.x - kFastRadius, area.y - kFastRadius, area.width + 2 * kFastRadius,
                            area.height + 2 * kFastRadius);
      found.clear();
      cv::FAST(level(window), found, thresholds.at<int>(cy, cx), true, cv::FastFeatureDetector::TYPE_9_16);
      for (cv::KeyPoint& kp : found) {
        kp.pt.x += static_cast<float>(window.x);
        kp.pt.y += static_cast<float>(window.y);
        if (area.contains(cv::Point(cvRound(kp.pt.x), cvRound(kp.pt.y)))) {
          corners.push_back(kp);
        }
      }
    }
  }
  return corners;
}

// Eqs 21-34 per cell: Otsu's threshold t by cv::threshold, I_mid the centre pixel, and
// C = max(c_min, round(threshold_scale |I_mid - t|)), at most 255; c_min for an empty cell.
inline cv::Mat cellThresholds(const cv::Mat& level, const ThresholdParams& params) {
  cv::Mat thresholds(params.grid_size, params.grid_size, CV_32S);
  for (int cy = 0; cy < params.grid_size; ++cy) {
    for (int cx = 0; cx < params.grid_size; ++cx) {
      const cv::Mat pixels = level(reference::cell(level.size(), params.grid_size, cx, cy));
      int c = params.c_min;
      if (!pixels.empty()) {
        cv::Mat binary;
        const double t = cv::threshold(pixels, binary, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
        const int i_mid = pixels.at<std::uint8_t>(pixels.rows / 2, pixels.cols / 2);
        c = std::min(
            255, std::max(params.c_min, static_cast<int>(std::lround(params.threshold_scale * std::abs(i_mid - t)))));
      }
      thresholds.at<int>(cy, cx) = c;
    }
  }
  return thresholds;
}

// The budget's shares (as ORB-SLAM): level l gets round(total (1 - 1/s) / (1 - (1/s)^n) (1/s)^l),
// no more than what is left, and the last level the remainder.
inline std::vector<int> budgets(int total, int n, double s) {
  std::vector<int> shares(static_cast<size_t>(n), 0);
  int left = total;
  for (int l = 0; l + 1 < n; ++l) {
    const double share = total * (1.0 - 1.0 / s) / (1.0 - std::pow(1.0 / s, n)) * std::pow(1.0 / s, l);
    shares[l] = std::min(static_cast<int>(std::lround(share)), left);
    left -= shares[l];
  }
  shares[n - 1] = left;
  return shares;
}

inline bool stronger(const cv::KeyPoint& a, const cv::KeyPoint& b) {
  if (a.response != b.response) {
    return a.response > b.response;
  }
  return a.pt.y != b.pt.y ? a.pt.y < b.pt.y : a.pt.x < b.pt.x;
}

// The n strongest, in their order of detection.
inline void keepStrongest(std::vector<cv::KeyPoint>& keypoints, size_t n) {
  if (keypoints.size() <= n) {
    return;
  }
  std::vector<cv::KeyPoint> sorted = keypoints;
  std::sort(sorted.begin(), sorted.end(), stronger);
  const cv::KeyPoint weakest = sorted[n - 1];
  std::vector<cv::KeyPoint> kept;
  for (const cv::KeyPoint& kp : keypoints) {
    if (!stronger(weakest, kp)) {
      kept.push_back(kp);
    }
  }
  keypoints = kept;
}

inline std::vector<cv::KeyPoint> selectSpread(std::vector<cv::KeyPoint> keypoints, int n, cv::Size size) {
  if (n <= 0) {
    return {};
  }
  if (static_cast<int>(keypoints.size()) <= n) {
    return keypoints;
  }
  const int cell = std::max(1, cvRound(std::sqrt(static_cast<double>(size.area()) / n)));
  const int cols = (size.width + cell - 1) / cell;
  const int rows = (size.height + cell - 1) / cell;
  std::vector<std::vector<cv::KeyPoint>> buckets(static_cast<size_t>(cols) * rows);
  for (const cv::KeyPoint& kp : keypoints) {
    const int bx = std::clamp(static_cast<int>(kp.pt.x) / cell, 0, cols - 1);
    const int by = std::clamp(static_cast<int>(kp.pt.y) / cell, 0, rows - 1);
    buckets[static_cast<size_t>(by) * cols + bx].push_back(kp);
  }
  for (auto& bucket : buckets) {
    std::sort(bucket.begin(), bucket.end(), stronger);
  }
  std::vector<cv::KeyPoint> selected;
  std::vector<cv::KeyPoint> round;
  for (size_t rank = 0; static_cast<int>(selected.size()) < n; ++rank) {
    round.clear();
    for (const auto& bucket : buckets) {
      if (rank < bucket.size()) {
        round.push_back(bucket[rank]);
      }
    }
    const size_t room = n - selected.size();
    if (round.size() > room) {
      std::sort(round.begin(), round.end(), stronger);
      round.resize(room);
    }
    selected.insert(selected.end(), round.begin(), round.end());
  }
  return selected;
}

inline void computeOrientation(const cv::Mat& level, std::vector<cv::KeyPoint>& keypoints) {
  constexpr int r = 15;
  const cv::Rect inside(r, r, level.cols - 2 * r, level.rows - 2 * r);
  for (cv::KeyPoint& kp : keypoints) {
    const cv::Point c(cvRound(kp.pt.x), cvRound(kp.pt.y));
    if (!inside.contains(c)) {
      kp.angle = 0.0f;
      continue;
    }
    int m01 = 0;
    int m10 = 0;
    for (int v = -r; v <= r; ++v) {
      for (int u = -r; u <= r; ++u) {
        if ((u * u + v * v) * 4 <= (2 * r + 1) * (2 * r + 1)) {  // within r + 1/2 of the centre
          const int value = level.at<std::uint8_t>(c.y + v, c.x + u);
          m10 += u * value;
          m01 += v * value;
        }
      }
    }
    kp.angle = cv::fastAtan2(static_cast<float>(m01), static_cast<float>(m10));
  }
}

// estimateNoise: the operator's response at every 4th row from the third on, |response| sorted,
// the lower median / (0.6745 * 6).
inline double noise(const cv::Mat& gray) {
  if (gray.rows < 5 || gray.cols < 5) {
    return 0.0;
  }
  cv::Mat response;
  const cv::Mat kernel =
      (cv::Mat_<float>(5, 5) << 1, 0, -2, 0, 1, 0, 0, 0, 0, 0, -2, 0, 4, 0, -2, 0, 0, 0, 0, 0, 1, 0, -2, 0, 1);
  cv::filter2D(gray, response, CV_32F, kernel);
  std::vector<float> values;
  for (int y = 2; y + 2 < gray.rows; y += 4) {
    for (int x = 2; x + 2 < gray.cols; ++x) {
      values.push_back(std::abs(response.at<float>(y, x)));
    }
  }
  std::sort(values.begin(), values.end());
  return values[(values.size() - 1) / 2] / (0.6745 * 6.0);
}

// OrbExtractor::extract, step by step.
inline Extraction extract(const cv::Mat& gray, const Params& params) {
  Extraction out;
  out.image = params.enhance_enabled ? reference::enhance(gray, params.enhance).image : gray;
  if (gray.empty()) {
    out.descriptors.create(0, kDescriptorBytes, CV_8U);
    return out;
  }
  const OrbParams& orb = params.orb;
  // cv::ORB's pyramid: each level the one above resized by OpenCV.
  std::vector<cv::Mat> pyramid{out.image};
  for (int level = 1; level < orb.n_levels; ++level) {
    const float inv_scale = 1.0f / static_cast<float>(std::pow(orb.scale_factor, level));
    const cv::Size size(cvRound(out.image.cols * inv_scale), cvRound(out.image.rows * inv_scale));
    if (size.width < 1 || size.height < 1) {
      break;
    }
    cv::Mat next;
    cv::resize(pyramid.back(), next, size, 0, 0, cv::INTER_LINEAR_EXACT);
    pyramid.push_back(next);
  }
  const int n_levels = static_cast<int>(pyramid.size());
  std::vector<std::vector<cv::KeyPoint>> level_keypoints(n_levels);
  for (int level = 0; level < n_levels; ++level) {
    cv::Mat thresholds =
        orb.threshold_mode == ThresholdMode::kAdaptive
            ? reference::cellThresholds(pyramid[level], params.threshold)
            : cv::Mat(params.threshold.grid_size, params.threshold.grid_size, CV_32S, cv::Scalar(orb.fast_threshold));
    level_keypoints[level] = reference::detectCorners(pyramid[level], thresholds);
    out.level_thresholds.push_back(thresholds);
  }
  out.cell_thresholds = out.level_thresholds.front();
  if (orb.max_features > 0) {
    const std::vector<int> budgets = reference::budgets(orb.max_features, orb.n_levels, orb.scale_factor);
    // The frame's noise floor: one noise estimate of the image the corners are found on.
    const double floor = orb.noise_floor > 0.0 ? orb.noise_floor * reference::noise(out.image) : 0.0;
    int carry = 0;
    for (int level = 0; level < n_levels; ++level) {
      const int budget = budgets[level] + carry;
      if (orb.noise_floor > 0.0) {
        const size_t share = static_cast<size_t>(std::max(0, budget));
        size_t above = 0;
        for (const cv::KeyPoint& kp : level_keypoints[level]) {
          above += kp.response >= floor;
        }
        if (orb.floor_candidate_ratio > 0.0) {  // at most that many times the budget of them
          above = std::min(above, static_cast<size_t>(std::ceil(orb.floor_candidate_ratio * share)));
        }
        reference::keepStrongest(level_keypoints[level], std::max(above, share));
      } else if (orb.candidate_ratio > 0.0) {
        reference::keepStrongest(level_keypoints[level], static_cast<size_t>(std::ceil(orb.candidate_ratio * budget)));
      }
      level_keypoints[level] =
          reference::selectSpread(std::move(level_keypoints[level]), budget, pyramid[level].size());
      carry = budget - static_cast<int>(level_keypoints[level].size());
    }
  }
  cv::Ptr<cv::ORB> describer = cv::ORB::create(500, 1.2f, 1, kEdgeThreshold, 0, 2, cv::ORB::HARRIS_SCORE, kPatchSize);
  std::vector<cv::Mat> level_descriptors;
  for (int level = 0; level < n_levels; ++level) {
    std::vector<cv::KeyPoint>& kps = level_keypoints[level];
    reference::computeOrientation(pyramid[level], kps);
    if (kps.empty()) {
      continue;
    }
    cv::Mat descriptors;
    describer->compute(pyramid[level], kps, descriptors);
    level_descriptors.push_back(descriptors);
    const float scale = static_cast<float>(std::pow(orb.scale_factor, level));
    for (cv::KeyPoint& kp : kps) {
      kp.pt *= scale;
      kp.size = kPatchSize * scale;
      kp.octave = level;
      out.keypoints.push_back(kp);
    }
  }
  if (level_descriptors.empty()) {
    out.descriptors.create(0, kDescriptorBytes, CV_8U);
  } else {
    cv::vconcat(level_descriptors, out.descriptors);
  }
  return out;
}

}  // namespace reference
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_TEST_REFERENCE_EXTRACTOR_H
