#include "enhanced_orb/camera_motion.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <opencv2/core/hal/hal.hpp>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/enhance.h"

namespace enhanced_orb {

// Phase correlation as cv::phaseCorrelate computes it (Hann window, normalised cross-power
// spectrum, peak of its inverse, centroid around the peak), written out so that the reference
// frame's spectrum is computed once and kept: one forward and one inverse DFT per frame instead
// of three and one (cv::phaseCorrelate on the same thumbnails took about 3x as long here). The
// transforms are OpenCV's own, planned once per thumbnail size (cv::hal::DFT2D): the same results
// as cv::dft, without the 7 allocations each cv::dft call makes.

void CameraMotion::reset() {
  reference_.release();
  previous_.release();
  reference_is_previous_ = false;
  reference_shift_ = cv::Point2d();
  // A moving start counts the first frame as one the camera left its last position on: held
  // moving for that frame, judged by the next one's shift from then on.
  since_moved_ = start_ == Start::kMoving ? kHoldFrames - 1 : kHoldFrames;
  shift_ = 0.0;
  new_scene_ = false;
  lambda_count_ = lambda_next_ = 0;
}

double CameraMotion::streamLambda() const {
  return lambda_count_ == 0 ? -1.0 : *std::min_element(lambdas_, lambdas_ + lambda_count_);
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
  level.convertTo(thumb_, CV_32F, 1.0, -cv::mean(level)[0]);             // less its mean
  cv::Mat windowed = padded_(cv::Rect(0, 0, thumb_.cols, thumb_.rows));  // the rest of padded_ stays 0
  cv::multiply(thumb_, window_, windowed);
  spectrum.create(padded_.size(), CV_32FC2);
  plans_.forward->apply(padded_.data, padded_.step, spectrum.data, spectrum.step);
}

CameraMotion::Correlation CameraMotion::correlate(const cv::Mat& first, const cv::Mat& second) {
  cv::mulSpectrums(first, second, cross_, 0, true);
  for (int y = 0; y < cross_.rows; ++y) {
    float* c = cross_.ptr<float>(y);  // re, im, re, im, ...
    for (int x = 0; x < 2 * cross_.cols; x += 2) {
      const float squared = c[x] * c[x] + c[x + 1] * c[x + 1];
      const float scale = squared > 1e-24f ? 1.0f / std::sqrt(squared) : 0.0f;
      c[x] *= scale;
      c[x + 1] *= scale;
    }
  }
  correlation_.create(cross_.size(), CV_32FC1);
  plans_.inverse->apply(cross_.data, cross_.step, correlation_.data, correlation_.step);
  cv::Point peak;
  double peak_value = 0.0;
  cv::minMaxLoc(correlation_, nullptr, &peak_value, nullptr, &peak);
  const int w = correlation_.cols, h = correlation_.rows;
  // The peak's strength: against the correlation's spread, and against the highest value outside
  // its 5 x 5 (the correlation wraps around).
  cv::Scalar mean, deviation;
  cv::meanStdDev(correlation_, mean, deviation);
  // The 5 x 5 set aside (its values kept, then put back in reverse order) for a second minMaxLoc.
  float kept[25];
  int k = 0;
  for (int dy = -2; dy <= 2; ++dy) {
    for (int dx = -2; dx <= 2; ++dx) {
      float& v = correlation_.at<float>((peak.y + dy + h) % h, (peak.x + dx + w) % w);
      kept[k++] = v;
      v = -std::numeric_limits<float>::max();
    }
  }
  double outside = 0.0;
  cv::minMaxLoc(correlation_, nullptr, &outside);
  for (int dy = 2; dy >= -2; --dy) {
    for (int dx = 2; dx >= -2; --dx) {
      correlation_.at<float>((peak.y + dy + h) % h, (peak.x + dx + w) % w) = kept[--k];
    }
  }
  const double second_highest = std::max(0.0, outside);
  Correlation result;
  result.strength = deviation[0] > 0.0 ? peak_value / deviation[0] : 0.0;
  result.peak_ratio = second_highest > 0.0 ? peak_value / second_highest : 0.0;
  // The centroid of the 3 x 3 around the peak.
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
  result.shift = cv::Point2d(x, y);
  return result;
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
      plans_ = Plans();
    }
  }
  lambdas_[lambda_next_] = imageLambda(gray);
  lambda_next_ = (lambda_next_ + 1) % kToneFrames;
  lambda_count_ = std::min(lambda_count_ + 1, kToneFrames);
  if (thumbnail_.width < kMinThumbnail || thumbnail_.height < kMinThumbnail) {
    return moving();  // too small to judge: still
  }
  if (!plans_.forward) {  // a new thumbnail size, or a copied CameraMotion: plans of its own
    plans_.forward = cv::hal::DFT2D::create(padded_.cols, padded_.rows, CV_32F, 1, 2, cv::DFT_COMPLEX_OUTPUT);
    plans_.inverse = cv::hal::DFT2D::create(padded_.cols, padded_.rows, CV_32F, 2, 1,
                                            cv::DFT_INVERSE | cv::DFT_SCALE | cv::DFT_REAL_OUTPUT);
  }
  if (reference_.empty()) {
    spectrumOf(gray, reference_);
    reference_.copyTo(previous_);
    reference_is_previous_ = true;
    reference_shift_ = cv::Point2d();
    shift_ = 0.0;
    new_scene_ = false;
    return moving();
  }
  spectrumOf(gray, spectrum_);
  // Whether this frame is a view of the last one's scene; then its shift from the last moved
  // frame: the reference's own shift from it plus the frame's from the reference (the same
  // correlation when the reference is the last frame). A reference whose peak is ambiguous (the
  // light or the view has changed too much since, as driving forward zooms it) gives no shift to
  // trust: this frame replaces it, with its shift from the last frame. (Carrying the shifts over
  // such a chain of references instead adds up their errors: a tripod's exposure bracket, 9 stops
  // from dark to bright, then drifts by more than a moved frame's shift.) The last frame decides
  // a new scene even where the reference seems to match: two dark frames of different scenes, a
  // few bright blobs each, can correlate in one clear peak.
  const Correlation last = correlate(previous_, spectrum_);
  new_scene_ = !last.related();
  cv::Point2d shift;
  bool is_reference = true;  // whether this frame becomes the reference
  if (new_scene_) {
    // The shift is measured from here anew; no evidence of motion nor of stillness: the hold runs on.
    // The stream's lambdas start anew with this frame's.
    lambdas_[0] = lambdas_[(lambda_next_ + kToneFrames - 1) % kToneFrames];
    lambda_count_ = lambda_next_ = 1;
    spectrum_.copyTo(reference_);
    reference_shift_ = shift;
  } else if (reference_is_previous_) {
    shift = reference_shift_ + last.shift;
    is_reference = false;
  } else {
    const Correlation from_reference = correlate(reference_, spectrum_);
    is_reference = !from_reference.unambiguous();
    if (is_reference) {
      shift = last.shift;
      spectrum_.copyTo(reference_);
      reference_shift_ = shift;
    } else {
      shift = reference_shift_ + from_reference.shift;
    }
  }
  const double scale = 1 << halves_.size();
  shift_ = std::hypot(shift.x, shift.y) * scale;
  if (shift_ >= std::max(kMovedFraction * gray.cols, kMinMovedShift * scale)) {
    spectrum_.copyTo(reference_);  // the moved frame is the new reference
    reference_shift_ = shift = cv::Point2d();
    is_reference = true;
    since_moved_ = 0;
  } else if (since_moved_ < kHoldFrames) {
    ++since_moved_;
  }
  reference_is_previous_ = is_reference;
  std::swap(previous_, spectrum_);
  return moving();
}

}  // namespace enhanced_orb
