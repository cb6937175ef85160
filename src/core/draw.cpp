#include "enhanced_orb/draw.h"

#include <array>
#include <cmath>

#include <opencv2/imgproc.hpp>

#include "enhanced_orb/adaptive_threshold.h"

namespace enhanced_orb {

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
  if (options.keypoints) {
    for (const cv::KeyPoint& kp : keypoints) {
      const cv::Scalar colour = octaveColour(kp.octave);
      const float radius = kp.size / 2.0f;
      const float angle = kp.angle * static_cast<float>(CV_PI / 180.0);
      const cv::Point2f tip = kp.pt + radius * cv::Point2f(std::cos(angle), std::sin(angle));
      cv::circle(canvas, kp.pt, cvRound(radius), colour, 1, cv::LINE_8);
      cv::line(canvas, kp.pt, tip, colour, 1, cv::LINE_8);
    }
  }
  if (options.text && !caption.empty()) {
    const cv::Point origin(8, 22);
    cv::putText(canvas, caption, origin, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
    cv::putText(canvas, caption, origin, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  }
  return canvas;
}

}  // namespace enhanced_orb
