#include "enhanced_orb/adaptive_threshold.h"

#include <cmath>
#include <cstdint>
#include <cstdlib>

#include <opencv2/imgproc.hpp>

namespace enhanced_orb {

cv::Rect gridCell(cv::Size size, int grid_size, int cx, int cy) {
  auto edge = [grid_size](int length, int k) {
    return static_cast<int>(std::lround(static_cast<double>(k) * length / grid_size));
  };
  const int x0 = edge(size.width, cx);
  const int y0 = edge(size.height, cy);
  return cv::Rect(x0, y0, edge(size.width, cx + 1) - x0, edge(size.height, cy + 1) - y0);
}

int otsuThreshold(const cv::Mat& cell) {
  if (cell.empty()) {
    return 0;
  }
  cv::Mat binary;  // required by the API, not used
  return static_cast<int>(cv::threshold(cell, binary, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU));
}

int centreValue(const cv::Mat& cell) {
  return cell.at<std::uint8_t>(cell.rows / 2, cell.cols / 2);
}

int cellThreshold(const cv::Mat& cell, const ThresholdParams& params) {
  if (cell.empty()) {
    return params.c_min;
  }
  const double c = params.threshold_scale * std::abs(centreValue(cell) - otsuThreshold(cell));  // eq 33
  return std::max(params.c_min, static_cast<int>(std::lround(c)));                              // eq 34
}

cv::Mat cellThresholds(const cv::Mat& image, const ThresholdParams& params) {
  cv::Mat thresholds(params.grid_size, params.grid_size, CV_32S);
  for (int cy = 0; cy < params.grid_size; ++cy) {
    for (int cx = 0; cx < params.grid_size; ++cx) {
      thresholds.at<int>(cy, cx) = cellThreshold(image(gridCell(image.size(), params.grid_size, cx, cy)), params);
    }
  }
  return thresholds;
}

}  // namespace enhanced_orb
