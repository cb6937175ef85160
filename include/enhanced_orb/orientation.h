// Eqs 4-6: a keypoint's orientation by the intensity centroid of its patch.
#ifndef ENHANCED_ORB_ORIENTATION_H
#define ENHANCED_ORB_ORIENTATION_H

#include <vector>

#include <opencv2/core.hpp>

namespace enhanced_orb {

// ORB's patch diameter; a keypoint of octave o has size kPatchSize * scale_factor^o.
constexpr int kPatchSize = 31;

// The angle (degrees, [0, 360)) of each keypoint by the intensity centroid of the circular patch of
// radius 15 around it. Keypoints whose patch leaves the image get angle 0.
void computeOrientation(const cv::Mat& level, std::vector<cv::KeyPoint>& keypoints);

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_ORIENTATION_H
