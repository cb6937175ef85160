// Section II-C: the image pyramid, as cv::ORB builds it.
#ifndef ENHANCED_ORB_PYRAMID_H
#define ENHANCED_ORB_PYRAMID_H

#include <vector>

#include <opencv2/core.hpp>

namespace enhanced_orb {

// scale_factor^level in single precision, as cv::ORB computes a level's scale.
float levelScale(double scale_factor, int level);

// The size of each level: level 0 is `size`, level i round(size / levelScale(i)); fewer than
// n_levels when a level would have no pixel.
void pyramidSizes(cv::Size size, int n_levels, double scale_factor, std::vector<cv::Size>& sizes);

// Level 0 is `image` (not copied), level i is level i-1 resized (INTER_LINEAR_EXACT, as cv::ORB)
// to its pyramidSizes() size. The extraction builds its levels the same way.
std::vector<cv::Mat> buildPyramid(const cv::Mat& image, int n_levels, double scale_factor);

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_PYRAMID_H
