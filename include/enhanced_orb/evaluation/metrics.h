// Measures: matching with cross-check, correct matches under a ground truth, repeatability, the
// ground truth of EuRoC frame pairs (epipolar geometry from the dataset's poses and calibration)
// and the relative pose a visual odometry front end would estimate from the matches.
#ifndef ENHANCED_ORB_EVALUATION_METRICS_H
#define ENHANCED_ORB_EVALUATION_METRICS_H

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

// Brute-force Hamming matching with cross-check (mutual nearest neighbours).
std::vector<cv::DMatch> mutualMatches(const cv::Mat& d1, const cv::Mat& d2);

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
  // The pose at `stamp` between the two poses around it (linear in position, along the geodesic in
  // rotation), if both lie within `tolerance_ns`; the pose itself at a recorded stamp.
  std::optional<cv::Matx44d> interpolated(std::int64_t stamp, std::int64_t tolerance_ns = 50000000) const;

private:
  std::map<std::int64_t, cv::Matx44d> poses_;
};

// Epipolar ground truth of two frames of one camera: a correspondence lies within `tolerance`
// pixels of the epipolar line of the other point, both ways (undistorted coordinates). Necessary,
// not sufficient: a wrong match along the epipolar line also passes.
GroundTruth epipolar(const Camera& camera, const cv::Matx44d& T_WB1, const cv::Matx44d& T_WB2, double tolerance = 3.0);
// The same for two cameras (a stereo pair: cam0 at one time, cam1 at another).
GroundTruth epipolar(const Camera& camera1, const cv::Matx44d& T_WB1, const Camera& camera2, const cv::Matx44d& T_WB2,
                     double tolerance = 3.0);

// The relative pose of camera 1 in camera 2 (x2 = R x1 + t) from two frames' ground-truth poses.
struct RelativePose {
  cv::Matx33d R;
  cv::Vec3d t;
};
RelativePose groundTruthPose(const Camera& camera1, const cv::Matx44d& T_WB1, const Camera& camera2,
                             const cv::Matx44d& T_WB2);

// Where the cameras barely moved (|t| < min_baseline metres), the epipolar test says nothing: such
// pairs are judged by the rotation alone (x2 = K2 R K1^-1 x1 on undistorted pixels, within tolerance).
bool isStatic(const RelativePose& pose, double min_baseline = 0.02);
GroundTruth rotationOnly(const Camera& camera1, const Camera& camera2, const RelativePose& pose,
                         double tolerance = 3.0);

// Relative pose from matched pixels, as a monocular front end estimates it: undistorted points,
// essential matrix by RANSAC (1 px, confidence 0.999), cheirality check. OpenCV's RANSAC draws its
// samples with a fixed seed, so `draw` 0 takes the matches in their order and draw k > 0 in an order
// shuffled by seed k: other samples, as another run of a front end would draw (poseOfDraws()).
struct PoseEstimate {
  bool ok = false;  // false: fewer than 5 matches or no essential matrix
  int inliers = 0;  // matches consistent with the estimate
  cv::Matx33d R;
  cv::Vec3d t;
};
PoseEstimate estimatePose(const Camera& camera1, const Camera& camera2, const std::vector<cv::Point2f>& p1,
                          const std::vector<cv::Point2f>& p2, int draw = 0);

// Angular errors in degrees: of the rotation, and of the translation's direction (sign-free, as the
// scale and sign of a monocular translation are not observable). Both 180 when `estimate` failed.
struct PoseError {
  double rotation_deg = 180.0;
  double translation_deg = 180.0;
  double max() const { return rotation_deg > translation_deg ? rotation_deg : translation_deg; }
};
PoseError poseError(const PoseEstimate& estimate, const RelativePose& truth);

// The pose of matched pixels estimated `draws` times (draws 0 to draws - 1 of estimatePose()) and
// the one whose error is the median (the lower of the two middle ones for an even count): a single
// RANSAC's luck moves a sequence's pose AUC by several hundredths (docs/RESULTS.md), the median of
// a few draws far less. draws <= 1: draw 0 alone.
struct DrawnPose {
  PoseEstimate estimate;
  PoseError error;
};
DrawnPose medianPoseOfDraws(const Camera& camera1, const Camera& camera2, const std::vector<cv::Point2f>& p1,
                            const std::vector<cv::Point2f>& p2, const RelativePose& truth, int draws);

// Area under the recall curve of `errors` up to `threshold`, normalised to [0, 1] (1: every error 0).
double poseAuc(std::vector<double> errors, double threshold);

}  // namespace evaluation
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_EVALUATION_METRICS_H
