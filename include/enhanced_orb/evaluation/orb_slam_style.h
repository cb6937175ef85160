// The extractor SLAM users run, as a rival: ORB-SLAM's ORBextractor written from its published
// description (Mur-Artal et al., ORB-SLAM, IEEE T-RO 2015, section III; ORB-SLAM2/3 documentation),
// not from its code: per pyramid level, FAST in grid cells of about 30 px with threshold
// `ini_fast`, falling back to `min_fast` in a cell where none is found; the level's share of the
// budget kept by a quadtree (nodes split until there are as many as the share, each node keeping
// its strongest corner); orientation by intensity centroid; rBRIEF on the level smoothed by a 7x7
// Gaussian (sigma 2), by cv::ORB, so the descriptors are the same kind as every other method's.
#ifndef ENHANCED_ORB_EVALUATION_ORB_SLAM_STYLE_H
#define ENHANCED_ORB_EVALUATION_ORB_SLAM_STYLE_H

#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

namespace enhanced_orb {
namespace evaluation {

struct OrbSlamStyleParams {
  int n_features = 1000;
  double scale_factor = 1.2;
  int n_levels = 8;
  int ini_fast = 20;
  int min_fast = 7;
  int cell = 30;  // grid cell side in pixels
};

class OrbSlamStyleExtractor {
public:
  explicit OrbSlamStyleExtractor(const OrbSlamStyleParams& params = OrbSlamStyleParams());
  // Keypoints in level-0 coordinates (octave, size 31 * scale, angle, response = FAST score) and
  // their descriptors; at most n_features of them.
  void extract(const cv::Mat& gray, std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors) const;

private:
  OrbSlamStyleParams params_;
  cv::Ptr<cv::ORB> describer_;
};

// The quadtree distribution of ORB-SLAM: the region [0, size) split into about width/height
// initial nodes, then every node holding more than one keypoint into four, until there are at
// least `n` nodes or none can be split (the last round splits the fullest nodes first and stops at
// `n`); each node keeps its strongest keypoint. Returns at most `n` keypoints.
std::vector<cv::KeyPoint> distributeQuadtree(const std::vector<cv::KeyPoint>& keypoints, cv::Rect2f region, int n);

}  // namespace evaluation
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_EVALUATION_ORB_SLAM_STYLE_H
