#include "enhanced_orb/pyramid.h"

#include <algorithm>
#include <cmath>

#include "enhanced_orb/simd.h"
#include "pyramid_levels.h"
#include "stopwatch.h"

namespace enhanced_orb {

float levelScale(double scale_factor, int level) {
  return static_cast<float>(std::pow(scale_factor, level));
}

void pyramidSizes(cv::Size size, int n_levels, double scale_factor, std::vector<cv::Size>& sizes) {
  sizes.assign(1, size);
  for (int level = 1; level < n_levels; ++level) {
    const float inv_scale = 1.0f / levelScale(scale_factor, level);
    const cv::Size next(cvRound(size.width * inv_scale), cvRound(size.height * inv_scale));
    if (next.width < 1 || next.height < 1) {
      break;
    }
    sizes.push_back(next);
  }
}

void PyramidLevels::reset(const cv::Mat& image, int n_levels, double scale_factor) {
  pyramidSizes(image.size(), n_levels, scale_factor, sizes_);
  levels_.resize(sizes_.size());
  images_.resize(std::max(images_.size(), sizes_.size()));
  resizes_.resize(std::max(resizes_.size(), sizes_.size()));
  levels_[0] = image;
  built_.store(1, std::memory_order_relaxed);
}

const cv::Mat& PyramidLevels::level(int l, double& ms) {
  if (built_.load(std::memory_order_acquire) > l) {
    return levels_[l];
  }
  Stopwatch clock;
  std::lock_guard<std::mutex> lock(mutex_);
  for (int next = built_.load(std::memory_order_relaxed); next <= l; ++next) {
    resizes_[next](levels_[next - 1], images_[next], sizes_[next], activeSimdLevel());
    levels_[next] = images_[next];
    built_.store(next + 1, std::memory_order_release);
  }
  ms += clock.lap();
  return levels_[l];
}

void PyramidLevels::releaseInput() {
  levels_.clear();
}

std::vector<cv::Mat> buildPyramid(const cv::Mat& image, int n_levels, double scale_factor) {
  PyramidLevels levels;
  levels.reset(image, n_levels, scale_factor);
  std::vector<cv::Mat> pyramid;
  double ms = 0.0;
  for (int l = 0; l < levels.count(); ++l) {
    pyramid.push_back(levels.level(l, ms));
  }
  return pyramid;
}

}  // namespace enhanced_orb
