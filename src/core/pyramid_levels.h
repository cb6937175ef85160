// The pyramid of one extraction, built as its levels are needed.
#ifndef ENHANCED_ORB_PYRAMID_LEVELS_H
#define ENHANCED_ORB_PYRAMID_LEVELS_H

#include <atomic>
#include <mutex>
#include <vector>

#include <opencv2/core.hpp>

#include "linear_resize.h"

namespace enhanced_orb {

// Level l is level l - 1 resized: whichever thread first needs a level builds it and the ones
// before it, in order, while other threads work on the levels already there. The images of levels
// 1.. are reused from frame to frame.
class PyramidLevels {
public:
  // A new frame: level 0 is `image` (not copied), sizes as pyramidSizes().
  void reset(const cv::Mat& image, int n_levels, double scale_factor);

  const std::vector<cv::Size>& sizes() const { return sizes_; }
  int count() const { return static_cast<int>(sizes_.size()); }

  // Level l, built first (with the levels before it) if no thread has yet; the time spent
  // building is added to `ms`. Safe to call from several threads.
  const cv::Mat& level(int l, double& ms);

  // Level l, which level() has returned since reset().
  const cv::Mat& built(int l) const { return levels_[l]; }

  // Lets go of level 0, which may be the caller's image.
  void releaseInput();

private:
  std::vector<cv::Size> sizes_;
  std::vector<cv::Mat> levels_;  // level 0 the frame's image, the others views of images_
  std::vector<cv::Mat> images_;  // the buffers of levels 1..
  std::vector<LinearResize> resizes_;
  std::mutex mutex_;
  std::atomic<int> built_{0};
};

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_PYRAMID_LEVELS_H
