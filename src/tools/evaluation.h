// Measures of ALGORITHM.md section 4: matching with cross-check, correct matches under a ground
// truth, repeatability; and the ground truth of EuRoC frame pairs (epipolar geometry from the
// dataset's poses and calibration).
#ifndef ENHANCED_ORB_TOOLS_EVALUATION_H
#define ENHANCED_ORB_TOOLS_EVALUATION_H

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace enhanced_orb {
namespace evaluation {

// Whether a point of image 1 and a point of image 2 correspond, by the ground truth.
using GroundTruth = std::function<bool(const cv::Point2f& p1, const cv::Point2f& p2)>;

// Points within `tolerance` pixels of each other (a photometric change of one frame).
GroundTruth identity(double tolerance = 3.0);

struct MatchCounts {
  int matches = 0;
  int correct = 0;
  double accuracy() const { return matches ? static_cast<double>(correct) / matches : 0.0; }
};

// Brute-force Hamming matching with cross-check; a match is correct when `truth` holds.
MatchCounts matchAndCount(const std::vector<cv::KeyPoint>& kp1, const cv::Mat& d1, const std::vector<cv::KeyPoint>& kp2,
                          const cv::Mat& d2, const GroundTruth& truth);

// Repeatability under the identity ground truth: the share of the smaller set's keypoints that have a
// keypoint of the other set within `tolerance` pixels, in [0, 1]. 0 when either set is empty.
double repeatability(const std::vector<cv::KeyPoint>& kp1, const std::vector<cv::KeyPoint>& kp2,
                     double tolerance = 3.0);

// A pinhole camera with radial-tangential distortion and its pose on the body (EuRoC sensor.yaml).
struct Camera {
  cv::Matx33d K;
  std::vector<double> distortion;  // k1, k2, p1, p2
  cv::Matx44d T_BS;                // sensor to body
};

// Reads mav0/<camera>/sensor.yaml; nullopt when missing or malformed.
std::optional<Camera> readCamera(const std::string& mav0, const std::string& camera);

// Body poses T_WB by timestamp [ns] (mav0/state_groundtruth_estimate0/data.csv).
class Trajectory {
public:
  static std::optional<Trajectory> read(const std::string& mav0);
  // The pose nearest to `stamp`, if one lies within `tolerance_ns`.
  std::optional<cv::Matx44d> at(std::int64_t stamp, std::int64_t tolerance_ns = 5000000) const;

private:
  std::map<std::int64_t, cv::Matx44d> poses_;
};

// Epipolar ground truth of two frames of one camera: a correspondence lies within `tolerance`
// pixels of the epipolar line of the other point, both ways (undistorted coordinates). Necessary,
// not sufficient: a wrong match along the epipolar line also passes.
GroundTruth epipolar(const Camera& camera, const cv::Matx44d& T_WB1, const cv::Matx44d& T_WB2, double tolerance = 3.0);

}  // namespace evaluation
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_TOOLS_EVALUATION_H
