// Real camera motion: stereo or monocular sequences with ground-truth camera poses (EuRoC ASL,
// KITTI odometry), light that changes over a sequence frame by frame, and what a SLAM front end is
// judged by on them: the relative pose between two frames and stereo frame-to-frame tracking.
#ifndef ENHANCED_ORB_EVALUATION_SEQUENCE_H
#define ENHANCED_ORB_EVALUATION_SEQUENCE_H

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/evaluation/dataset.h"
#include "enhanced_orb/evaluation/metrics.h"

namespace enhanced_orb {
namespace evaluation {

// A sequence with a ground-truth pose for every frame kept: frames without one are dropped.
struct Sequence {
  std::string name;                       // the folder's name
  std::string format;                     // "euroc" or "kitti"
  double rate_hz = 20.0;                  // frame rate
  Camera left;                            // the camera of `frames`
  std::optional<Camera> right;            // the second camera of a stereo rig (T_BS relative to the same body)
  std::vector<std::string> frames;        // left images
  std::vector<std::string> right_frames;  // right images at the same times (empty: monocular)
  std::vector<cv::Matx44d> poses;         // T_WB of each frame (the body; camera pose = T_WB * left.T_BS)
};

// A EuRoC ASL folder (DIR or DIR/mav0) with cam0 (and cam1) sensor.yaml, data.csv and
// state_groundtruth_estimate0, the files read as ETH ships them; poses interpolated to the frame
// times (linear in position, spherical in rotation). Throws DatasetError naming what is missing.
Sequence readEurocSequence(const std::string& dir);

// A KITTI odometry sequence folder: image_0/*.png (image_1 for stereo), calib.txt (P0, P1) and the
// poses as poses.txt beside them or given as `poses_file` (KITTI ships them in poses/NN.txt);
// images are rectified, so distortion is zero; 10 Hz. Throws DatasetError naming what is missing.
Sequence readKittiSequence(const std::string& dir, const std::string& poses_file = "");

// EuRoC when DIR (or DIR/mav0) holds cam0/data.csv, KITTI when it holds calib.txt.
Sequence readSequence(const std::string& dir);

// The frame gaps of the relative-pose test for a frame rate: 1, 5, 10 frames at 20 Hz (0.05, 0.25,
// 0.5 s); 1, 3, 5 at 10 Hz (0.1, 0.3, 0.5 s): about the same times at other rates.
std::vector<int> defaultGaps(double rate_hz);

// Light that changes over a sequence, frame by frame, through the sensor model of lowLight()
// (electrons_per_dn 2, read noise 3 e-). Every condition is deterministic for a seed, and each
// frame is degraded on its own (its own noise).
//   unchanged   the frames as recorded
//   dim         x0.25 light, gain 2
//   dark        x0.06 light, gain 4
//   dusk        the light falls log-linearly from x1 to x0.05 over the sequence; auto gain
//   lights_out  the light falls to x0.1 in the middle of the sequence; auto gain catches up over
//               about 10 frames
//   flicker     alternate frames at x1 and x0.5 (faster than any auto gain)
//   lamp        a dark room (x0.03) lit by a lamp carried with the camera: bright centre, dark edges
//   dip         x0.02 of the light over frames 100-249 (of 300; scaled to the sequence); auto gain
// Auto gain: the gain that would restore the light (1 / light), capped at 8; it moves a quarter of
// the way (in log) towards it each frame.
struct LightCondition {
  std::string name;
  // Frame `frame` of `n_frames` under this condition.
  cv::Mat apply(const cv::Mat& gray, int frame, int n_frames, std::uint64_t seed) const;
  // The light falling on the scene and the sensor gain at a frame.
  double light(int frame, int n_frames) const;
  double gain(int frame, int n_frames) const;
  // What the condition does over a sequence of `n_frames` frames, in a line (the frames and factors
  // light() and apply() use), e.g. for a report's legend.
  std::string describe(int n_frames) const;
};
std::vector<LightCondition> lightConditions();

// Each frame's CameraMotion judgment, the frames fed in order as one camera's stream: what a
// stream's extractor with camera_motion auto reads (Method::run).
std::vector<StreamJudgment> judgeMotion(const std::vector<cv::Mat>& frames);

// Relative pose from a monocular pair of a sequence: the ground truth of frame j relative to frame i.
RelativePose sequencePose(const Sequence& sequence, int i, int j);

// One stereo frame's map: points triangulated from left-right matches (mutual nearest neighbours,
// undistorted, positive depth within 0.1-40 m in both cameras, reprojected within 2 px in both),
// in the left camera's frame, each with its left keypoint's descriptor.
struct StereoMap {
  std::vector<cv::Point3f> points;
  cv::Mat descriptors;
  int stereo_matches = 0;
};
StereoMap triangulateStereo(const Camera& left, const Camera& right, const std::vector<cv::KeyPoint>& kp_left,
                            const cv::Mat& d_left, const std::vector<cv::KeyPoint>& kp_right, const cv::Mat& d_right);

// Tracking the next left frame against a map, as a stereo SLAM front end tracks from frame to frame:
// mutual nearest neighbours between the map's and the frame's descriptors, PnP with RANSAC (2 px,
// a fixed seed), then the motion x_next = R x_map + t compared with the ground truth. Tracked: at
// least kMinTrackingInliers inliers and the motion within kTrackingRotationDeg degrees and
// kTrackingTranslationM metres of the truth.
constexpr int kMinTrackingInliers = 20;
constexpr double kTrackingRotationDeg = 1.0;
constexpr double kTrackingTranslationM = 0.03;
struct TrackResult {
  int matches = 0;
  int inliers = 0;
  bool solved = false;          // PnP found a motion
  double rotation_deg = 180.0;  // error against the truth (180 when not solved)
  double translation_m = 1e9;   // error against the truth (1e9 when not solved)
  bool tracked() const {
    return solved && inliers >= kMinTrackingInliers && rotation_deg <= kTrackingRotationDeg &&
           translation_m <= kTrackingTranslationM;
  }
};
TrackResult trackFrame(const StereoMap& map, const Camera& camera, const std::vector<cv::KeyPoint>& keypoints,
                       const cv::Mat& descriptors, const RelativePose& truth);

}  // namespace evaluation
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_EVALUATION_SEQUENCE_H
