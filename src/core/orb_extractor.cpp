#include "enhanced_orb/orb_extractor.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "enhanced_orb/adaptive_threshold.h"
#include "enhanced_orb/enhance.h"
#include "enhanced_orb/simd.h"
#include "kernels/fast_score.h"

namespace enhanced_orb {
namespace {

constexpr int kOrientationRadius = 15;

class Stopwatch {
public:
  // Milliseconds since the last call (or construction).
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
    return ms;
  }

private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

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

float levelScale(double scale_factor, int level) {
  return static_cast<float>(std::pow(scale_factor, level));
}

}  // namespace

double StageTimings::extractMs() const {
  return pyramid_ms + threshold_ms + fast_ms + select_ms + orientation_ms + descriptor_ms;
}

std::vector<cv::Mat> buildPyramid(const cv::Mat& image, int n_levels, double scale_factor) {
  std::vector<cv::Mat> pyramid{image};
  for (int level = 1; level < n_levels; ++level) {
    const float inv_scale = 1.0f / levelScale(scale_factor, level);
    const cv::Size size(cvRound(image.cols * inv_scale), cvRound(image.rows * inv_scale));
    if (size.width < 1 || size.height < 1) {
      break;
    }
    cv::Mat next;
    cv::resize(pyramid.back(), next, size, 0, 0, cv::INTER_LINEAR_EXACT);
    pyramid.push_back(next);
  }
  return pyramid;
}

void detectCorners(const cv::Mat& level, const cv::Mat& thresholds, cv::Mat& scores,
                   std::vector<cv::KeyPoint>& corners) {
  CV_Assert(level.type() == CV_8UC1 && thresholds.type() == CV_32S && thresholds.rows == thresholds.cols);
  corners.clear();
  const cv::Rect interior(kEdgeThreshold, kEdgeThreshold, level.cols - 2 * kEdgeThreshold,
                          level.rows - 2 * kEdgeThreshold);
  if (interior.width <= 0 || interior.height <= 0) {
    return;
  }
  const int grid = thresholds.rows;
  // cv::FAST clamps its threshold to [0, 255]; no pixel scores at or below the smallest one of the
  // level can be a corner or weigh in a suppression, so the kernel may skip those.
  cv::Mat clamped;
  cv::min(cv::max(thresholds, 0), 255, clamped);
  double lowest = 0.0;
  cv::minMaxLoc(clamped, &lowest);

  // One score per interior pixel, in a map of the level's size (only the interior is written).
  scores.create(level.size(), CV_8UC1);
  const SimdLevel simd = activeSimdLevel();
  for (int y = interior.y; y < interior.br().y; ++y) {
    kernels::fastScoreRow(simd, level.ptr<std::uint8_t>(y) + interior.x, static_cast<std::ptrdiff_t>(level.step),
                          interior.width, scores.ptr<std::uint8_t>(y) + interior.x, static_cast<int>(lowest));
  }

  // cv::FAST run on each cell's window (the cell widened by 3, where its circle reads) keeps a
  // corner when its score exceeds that of each of its 8 neighbours, a neighbour counting 0 unless
  // it lies in the cell and is a corner at the cell's threshold. Corners come cell by cell
  // (row-major), each cell row by row.
  for (int cy = 0; cy < grid; ++cy) {
    for (int cx = 0; cx < grid; ++cx) {
      const cv::Rect cell = gridCell(level.size(), grid, cx, cy) & interior;
      if (cell.empty()) {
        continue;
      }
      const int t = clamped.at<int>(cy, cx);
      const int x_end = cell.br().x;
      const int y_end = cell.br().y;
      auto neighbour = [&](int x, int y) -> int {
        if (x < cell.x || x >= x_end || y < cell.y || y >= y_end) {
          return 0;
        }
        const int m = scores.at<std::uint8_t>(y, x);
        return m > t ? m - 1 : 0;
      };
      for (int y = cell.y; y < y_end; ++y) {
        const std::uint8_t* row = scores.ptr<std::uint8_t>(y);
        for (int x = cell.x; x < x_end; ++x) {
          if (row[x] <= t) {
            continue;
          }
          const int score = row[x] - 1;  // cv::FAST's corner score
          if (score > neighbour(x - 1, y - 1) && score > neighbour(x, y - 1) && score > neighbour(x + 1, y - 1) &&
              score > neighbour(x - 1, y) && score > neighbour(x + 1, y) && score > neighbour(x - 1, y + 1) &&
              score > neighbour(x, y + 1) && score > neighbour(x + 1, y + 1)) {
            corners.emplace_back(static_cast<float>(x), static_cast<float>(y), 7.0f, -1.0f, static_cast<float>(score));
          }
        }
      }
    }
  }
}

std::vector<cv::KeyPoint> detectCorners(const cv::Mat& level, const cv::Mat& thresholds) {
  cv::Mat scores;
  std::vector<cv::KeyPoint> corners;
  detectCorners(level, thresholds, scores, corners);
  return corners;
}

std::vector<int> levelBudgets(int total, int n_levels, double scale_factor) {
  std::vector<int> budgets(n_levels, 0);
  const double factor = 1.0 / scale_factor;
  double per_level = total * (1.0 - factor) / (1.0 - std::pow(factor, n_levels));
  int assigned = 0;
  for (int level = 0; level + 1 < n_levels; ++level) {
    budgets[level] = std::min(cvRound(per_level), total - assigned);
    assigned += budgets[level];
    per_level *= factor;
  }
  budgets[n_levels - 1] = total - assigned;
  return budgets;
}

namespace {

// Stronger response first; position breaks ties, so that every selection is deterministic.
bool stronger(const cv::KeyPoint& a, const cv::KeyPoint& b) {
  if (a.response != b.response) {
    return a.response > b.response;
  }
  return a.pt.y != b.pt.y ? a.pt.y < b.pt.y : a.pt.x < b.pt.x;
}

}  // namespace

void keepStrongest(std::vector<cv::KeyPoint>& keypoints, size_t n) {
  if (keypoints.size() <= n) {
    return;
  }
  std::nth_element(keypoints.begin(), keypoints.begin() + static_cast<std::ptrdiff_t>(n), keypoints.end(), stronger);
  keypoints.resize(n);
}

std::vector<cv::KeyPoint> selectSpread(std::vector<cv::KeyPoint> keypoints, int n, cv::Size size) {
  if (n <= 0) {
    return {};
  }
  if (static_cast<int>(keypoints.size()) <= n) {
    return keypoints;
  }
  const int cell = std::max(1, cvRound(std::sqrt(static_cast<double>(size.area()) / n)));
  const int cols = (size.width + cell - 1) / cell;
  const int rows = (size.height + cell - 1) / cell;
  const auto better = stronger;
  std::vector<std::vector<cv::KeyPoint>> buckets(static_cast<size_t>(cols) * rows);
  for (const cv::KeyPoint& kp : keypoints) {
    const int bx = std::clamp(static_cast<int>(kp.pt.x) / cell, 0, cols - 1);
    const int by = std::clamp(static_cast<int>(kp.pt.y) / cell, 0, rows - 1);
    buckets[static_cast<size_t>(by) * cols + bx].push_back(kp);
  }
  for (auto& bucket : buckets) {
    std::sort(bucket.begin(), bucket.end(), better);
  }
  // Round r takes the r-th best of every cell; the last, partial round keeps its best responses.
  std::vector<cv::KeyPoint> selected;
  selected.reserve(n);
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
      std::partial_sort(round.begin(), round.begin() + room, round.end(), better);
      round.resize(room);
    }
    selected.insert(selected.end(), round.begin(), round.end());
  }
  return selected;
}

void computeOrientation(const cv::Mat& level, std::vector<cv::KeyPoint>& keypoints) {
  static const std::array<int, kOrientationRadius + 1> u_max = patchHalfWidths();
  const cv::Rect inside(kOrientationRadius, kOrientationRadius, level.cols - 2 * kOrientationRadius,
                        level.rows - 2 * kOrientationRadius);
  const int step = static_cast<int>(level.step1());
  for (cv::KeyPoint& kp : keypoints) {
    const cv::Point c(cvRound(kp.pt.x), cvRound(kp.pt.y));
    if (!inside.contains(c)) {
      kp.angle = 0.0f;
      continue;
    }
    // Eq 4: moments m_pq = sum x^p y^q I(x, y) over the patch, centred on the keypoint.
    const std::uint8_t* centre = level.ptr<std::uint8_t>(c.y) + c.x;
    int m01 = 0;
    int m10 = 0;
    for (int v = -kOrientationRadius; v <= kOrientationRadius; ++v) {
      const std::uint8_t* row = centre + v * step;
      const int half = u_max[std::abs(v)];
      int row_sum = 0;
      for (int u = -half; u <= half; ++u) {
        m10 += u * row[u];
        row_sum += row[u];
      }
      m01 += v * row_sum;
    }
    kp.angle = cv::fastAtan2(static_cast<float>(m01), static_cast<float>(m10));  // eqs 5-6
  }
}

OrbExtractor::OrbExtractor(const Params& params) : params_(params) {
  const std::vector<std::string> problems = validate(params_);
  if (!problems.empty()) {
    throw std::invalid_argument(joinMessages(problems));
  }
  // One level: the extractor hands cv::ORB one pyramid level at a time, keypoints at octave 0.
  describer_ = cv::ORB::create(500, 1.2f, 1, kEdgeThreshold, 0, 2, cv::ORB::HARRIS_SCORE, kPatchSize);
}

Extraction OrbExtractor::extract(const cv::Mat& gray) const {
  if (!gray.empty() && gray.type() != CV_8UC1) {
    throw std::invalid_argument("extract: expected CV_8UC1, got " + cv::typeToString(gray.type()));
  }
  Extraction out;
  Stopwatch clock;
  if (params_.enhance_enabled) {
    EnhanceResult enhanced = enhance(gray, params_.enhance);
    out.image = enhanced.image;
    out.lambda = enhanced.lambda;
    out.poor_quality = enhanced.poor_quality;
    out.inverted = enhanced.inverted;
  } else {
    out.image = gray;
  }
  out.timings.enhance_ms = clock.lap();

  const OrbParams& orb = params_.orb;
  const std::vector<cv::Mat> pyramid = buildPyramid(out.image, orb.n_levels, orb.scale_factor);
  out.timings.pyramid_ms = clock.lap();

  const int n_levels = static_cast<int>(pyramid.size());
  std::vector<std::vector<cv::KeyPoint>> level_keypoints(n_levels);
  for (int level = 0; level < n_levels; ++level) {
    cv::Mat thresholds =
        orb.threshold_mode == ThresholdMode::kAdaptive
            ? cellThresholds(pyramid[level], params_.threshold)
            : cv::Mat(params_.threshold.grid_size, params_.threshold.grid_size, CV_32S, cv::Scalar(orb.fast_threshold));
    out.timings.threshold_ms += clock.lap();
    level_keypoints[level] = detectCorners(pyramid[level], thresholds);
    out.level_thresholds.push_back(thresholds);
    out.timings.fast_ms += clock.lap();
  }
  out.cell_thresholds = out.level_thresholds.front();

  if (orb.max_features > 0) {
    // Budget per level; what a level cannot use passes on to the next one.
    const std::vector<int> budgets = levelBudgets(orb.max_features, orb.n_levels, orb.scale_factor);
    int carry = 0;
    for (int level = 0; level < n_levels; ++level) {
      const int budget = budgets[level] + carry;
      if (orb.candidate_ratio > 0.0) {
        keepStrongest(level_keypoints[level], static_cast<size_t>(std::ceil(orb.candidate_ratio * budget)));
      }
      level_keypoints[level] = selectSpread(std::move(level_keypoints[level]), budget, pyramid[level].size());
      carry = budget - static_cast<int>(level_keypoints[level].size());
    }
  }
  out.timings.select_ms = clock.lap();

  for (int level = 0; level < n_levels; ++level) {
    computeOrientation(pyramid[level], level_keypoints[level]);
  }
  out.timings.orientation_ms = clock.lap();

  std::vector<cv::Mat> level_descriptors;
  for (int level = 0; level < n_levels; ++level) {
    std::vector<cv::KeyPoint>& kps = level_keypoints[level];
    if (kps.empty()) {
      continue;
    }
    const size_t count = kps.size();
    cv::Mat descriptors;
    describer_->compute(pyramid[level], kps, descriptors);
    // Every keypoint lies kEdgeThreshold inside the level, so cv::ORB must keep them all, in order.
    CV_Assert(kps.size() == count && descriptors.rows == static_cast<int>(count));
    level_descriptors.push_back(descriptors);

    const float scale = levelScale(orb.scale_factor, level);
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
  out.timings.descriptor_ms = clock.lap();
  return out;
}

}  // namespace enhanced_orb
