#include "enhanced_orb/draw.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "enhanced_orb/adaptive_threshold.h"
#include "enhanced_orb/orb_extractor.h"

namespace enhanced_orb {
namespace {

// White text with a dark outline: readable on any background.
void outlinedText(cv::Mat& canvas, const std::string& text, cv::Point origin, double scale) {
  cv::putText(canvas, text, origin, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
  cv::putText(canvas, text, origin, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
}

}  // namespace

cv::Scalar octaveColour(int octave) {
  static const std::array<cv::Scalar, 8> palette = {
      cv::Scalar(0, 255, 0),   cv::Scalar(0, 200, 255), cv::Scalar(255, 128, 0), cv::Scalar(255, 0, 255),
      cv::Scalar(0, 255, 255), cv::Scalar(255, 255, 0), cv::Scalar(0, 0, 255),   cv::Scalar(128, 128, 255)};
  return palette[static_cast<size_t>(std::abs(octave)) % palette.size()];
}

cv::Mat drawAnnotated(const cv::Mat& image, const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& thresholds,
                      const std::string& caption, const DrawOptions& options, cv::Mat canvas) {
  if (image.empty()) {
    return cv::Mat();
  }
  if (image.channels() == 1) {
    cv::cvtColor(image, canvas, cv::COLOR_GRAY2BGR);
  } else {
    image.copyTo(canvas);
  }
  if (options.grid && !thresholds.empty()) {
    const int grid = thresholds.rows;
    for (int cy = 0; cy < grid; ++cy) {
      for (int cx = 0; cx < grid; ++cx) {
        const cv::Rect cell = gridCell(canvas.size(), grid, cx, cy);
        cv::rectangle(canvas, cell, cv::Scalar(255, 255, 255), 1);
        cv::putText(canvas, std::to_string(thresholds.at<int>(cy, cx)), cell.tl() + cv::Point(4, 14),
                    cv::FONT_HERSHEY_PLAIN, 1.0, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
      }
    }
  }
  int max_octave = -1;
  if (options.keypoints) {
    const bool all = options.max_drawn <= 0 || static_cast<int>(keypoints.size()) <= options.max_drawn;
    const std::vector<cv::KeyPoint> drawn = all ? keypoints : selectSpread(keypoints, options.max_drawn, canvas.size());
    for (const cv::KeyPoint& kp : drawn) {
      const cv::Scalar colour = octaveColour(kp.octave);
      const int radius = 1 + std::max(0, kp.octave) / 2;
      max_octave = std::max(max_octave, kp.octave);
      if (options.orientation) {
        const float angle = kp.angle * static_cast<float>(CV_PI / 180.0);
        const cv::Point2f tip = kp.pt + (radius + 4.0f) * cv::Point2f(std::cos(angle), std::sin(angle));
        cv::line(canvas, kp.pt, tip, colour, 1, cv::LINE_8);
      }
      cv::circle(canvas, kp.pt, radius, colour, cv::FILLED, cv::LINE_8);
    }
  }
  if (options.text) {
    if (!caption.empty()) {
      outlinedText(canvas, caption, cv::Point(8, 20), 0.5);
    }
    // Legend: one coloured dot per octave drawn, bottom left.
    for (int o = 0; o <= max_octave; ++o) {
      const cv::Point at(12 + 34 * o, canvas.rows - 10);
      cv::circle(canvas, at, 1 + o / 2, octaveColour(o), cv::FILLED, cv::LINE_8);
      outlinedText(canvas, std::to_string(o), at + cv::Point(6, 5), 0.4);
    }
  }
  return canvas;
}

}  // namespace enhanced_orb
