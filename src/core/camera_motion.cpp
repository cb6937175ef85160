#include "enhanced_orb/camera_motion.h"

#include <algorithm>
#include <cmath>

#include <opencv2/imgproc.hpp>

namespace enhanced_orb {

// Phase correlation as cv::phaseCorrelate computes it (Hann window, normalised cross-power
// spectrum, peak of its inverse, centroid around the peak), written out so that the reference
// frame's spectrum is computed once and kept: one forward and one inverse DFT per frame instead
// of three and one (cv::phaseCorrelate on the same thumbnails took about 3x as long here).

void CameraMotion::reset() {
  reference_.release();
  since_moved_ = kHoldFrames;
  shift_ = 0.0;
}

void CameraMotion::spectrumOf(const cv::Mat& gray, cv::Mat& spectrum) {
  // Halved by INTER_AREA (2 x 2 means, OpenCV's fast path) as often as halves_ has levels: one
  // resize by the whole factor took about 5x as long here.
  cv::Mat level = gray;
  for (cv::Mat& half : halves_) {
    cv::resize(level(cv::Rect(0, 0, level.cols & ~1, level.rows & ~1)), half, cv::Size(level.cols / 2, level.rows / 2),
               0, 0, cv::INTER_AREA);
    level = half;
  }
  level.convertTo(thumb_, CV_32F);
  thumb_ -= cv::mean(thumb_)[0];
  cv::Mat windowed = padded_(cv::Rect(0, 0, thumb_.cols, thumb_.rows));  // the rest of padded_ stays 0
  cv::multiply(thumb_, window_, windowed);
  cv::dft(padded_, spectrum, cv::DFT_COMPLEX_OUTPUT);
}

double CameraMotion::shiftTo(const cv::Mat& spectrum) {
  cv::mulSpectrums(reference_, spectrum, cross_, 0, true);
  for (int y = 0; y < cross_.rows; ++y) {
    float* c = cross_.ptr<float>(y);  // re, im, re, im, ...
    for (int x = 0; x < 2 * cross_.cols; x += 2) {
      const float squared = c[x] * c[x] + c[x + 1] * c[x + 1];
      const float scale = squared > 1e-24f ? 1.0f / std::sqrt(squared) : 0.0f;
      c[x] *= scale;
      c[x + 1] *= scale;
    }
  }
  cv::dft(cross_, correlation_, cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
  cv::Point peak;
  cv::minMaxLoc(correlation_, nullptr, nullptr, nullptr, &peak);
  // The centroid of the 3 x 3 around the peak (the correlation wraps around).
  const int w = correlation_.cols, h = correlation_.rows;
  double sum = 0.0, sx = 0.0, sy = 0.0;
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const float v = correlation_.at<float>((peak.y + dy + h) % h, (peak.x + dx + w) % w);
      if (v > 0.0f) {
        sum += v;
        sx += v * dx;
        sy += v * dy;
      }
    }
  }
  double x = peak.x + (sum > 0.0 ? sx / sum : 0.0);
  double y = peak.y + (sum > 0.0 ? sy / sum : 0.0);
  x = x > w / 2.0 ? x - w : x;  // shifts past half the size are negative ones
  y = y > h / 2.0 ? y - h : y;
  return std::hypot(x, y);
}

bool CameraMotion::update(const cv::Mat& gray) {
  if (gray.empty() || gray.type() != CV_8UC1) {
    return moving();
  }
  if (gray.size() != frame_size_) {
    reset();
    frame_size_ = gray.size();
    // Halve while the half is at least kThumbnailWidth wide.
    thumbnail_ = frame_size_;
    int halvings = 0;
    while (thumbnail_.width / 2 >= kThumbnailWidth && thumbnail_.height / 2 >= kMinThumbnail) {
      thumbnail_ = cv::Size(thumbnail_.width / 2, thumbnail_.height / 2);
      ++halvings;
    }
    halves_.resize(halvings);
    if (thumbnail_.width >= kMinThumbnail && thumbnail_.height >= kMinThumbnail) {
      cv::createHanningWindow(window_, thumbnail_, CV_32F);
      padded_ =
          cv::Mat::zeros(cv::getOptimalDFTSize(thumbnail_.height), cv::getOptimalDFTSize(thumbnail_.width), CV_32F);
    }
  }
  if (thumbnail_.width < kMinThumbnail || thumbnail_.height < kMinThumbnail) {
    return moving();  // too small to judge: still
  }
  if (reference_.empty()) {
    spectrumOf(gray, reference_);
    shift_ = 0.0;
    return moving();
  }
  spectrumOf(gray, spectrum_);
  shift_ = shiftTo(spectrum_) * (1 << halves_.size());
  if (shift_ >= kMovedFraction * gray.cols) {
    std::swap(reference_, spectrum_);  // the moved frame is the new reference
    since_moved_ = 0;
  } else if (since_moved_ < kHoldFrames) {
    ++since_moved_;
  }
  return moving();
}

}  // namespace enhanced_orb
