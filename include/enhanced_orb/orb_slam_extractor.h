// enhanced_orb in place of ORB-SLAM2/3's ORBextractor: the same constructor, call operators,
// scale accessors and public image pyramid, so that a `using` or a type change in ORB-SLAM is all
// a user edits (docs/ORB_SLAM3.md says which lines).
//
// ORB-SLAM's FAST pair maps onto this package's parameters: iniThFAST (20) is `fast_threshold`,
// the threshold of the fixed-threshold modes (baseline); minThFAST (7) is `c_min`, the floor of the
// adaptive per-cell threshold, which plays the part of ORB-SLAM's fallback in cells with no corner.
// nfeatures, scaleFactor and nlevels are `max_features`, `scale_factor` and `n_levels`. The other
// parameters come from `base`; the five-argument constructor takes them from the YAML file named by
// the environment variable ENHANCED_ORB_CONFIG (readParamsFile(): a `preset` and/or parameters by
// their ROS names, e.g. the package's config/motion.yaml) or, without it, the default mode; unless
// the file sets moving_gamma_mode, a moving camera's frames all get the tone curve (always: a SLAM
// map matches frames against points described under earlier light, docs/ORB_SLAM3.md). Each
// extractor takes one camera's frames in order (as ORB-SLAM calls it), so camera_motion auto
// judges from them whether the camera moves; the first frame counts as a moving camera's
// (CameraMotion::Start::kMoving), as ORB-SLAM starts its map from the first frames of one.
//
// This header needs only C++11 and OpenCV (ORB-SLAM builds as C++11 or C++14); the rest of the
// package is C++17 behind it.
#ifndef ENHANCED_ORB_ORB_SLAM_EXTRACTOR_H
#define ENHANCED_ORB_ORB_SLAM_EXTRACTOR_H

#include <memory>
#include <vector>

#include <opencv2/core.hpp>

namespace enhanced_orb {

struct Params;

class OrbSlamExtractor {
public:
  // Throws std::invalid_argument when a value is out of range (validate()).
  OrbSlamExtractor(int nfeatures, float scaleFactor, int nlevels, int iniThFAST, int minThFAST);
  OrbSlamExtractor(int nfeatures, float scaleFactor, int nlevels, int iniThFAST, int minThFAST, const Params& base);
  ~OrbSlamExtractor();

  // ORB-SLAM3: keypoints (level-0 coordinates, octave, angle, size 31 x scale) and their
  // descriptors, those whose x lies in [vLappingArea[0], vLappingArea[1]] placed after the others
  // (filled from the end, as ORB-SLAM3 does); returns how many come first (the monocular ones).
  // An empty image gives -1, as ORB-SLAM3. 8-bit gray or BGR/BGRA input; the mask, if not empty,
  // 8-bit of the image's size: no keypoint where it is 0. mvImagePyramid holds the levels after.
  int operator()(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                 cv::OutputArray descriptors, std::vector<int>& vLappingArea);
  // ORB-SLAM2: the same without a lapping area.
  void operator()(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                  cv::OutputArray descriptors);

  int GetLevels() const { return static_cast<int>(mvScaleFactor.size()); }
  float GetScaleFactor() const { return scale_factor_; }
  std::vector<float> GetScaleFactors() const { return mvScaleFactor; }
  std::vector<float> GetInverseScaleFactors() const { return mvInvScaleFactor; }
  std::vector<float> GetScaleSigmaSquares() const { return mvLevelSigma2; }
  std::vector<float> GetInverseScaleSigmaSquares() const { return mvInvLevelSigma2; }

  const Params& params() const;

  // Per level, the image the keypoints were found on (the enhanced frame and its pyramid), of
  // size round(cols / scale) x round(rows / scale); ORB-SLAM's stereo matching reads it.
  std::vector<cv::Mat> mvImagePyramid;

private:
  struct State;  // the extractor and its reused result
  std::unique_ptr<State> state_;
  float scale_factor_;
  std::vector<float> mvScaleFactor, mvInvScaleFactor, mvLevelSigma2, mvInvLevelSigma2;
};

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_ORB_SLAM_EXTRACTOR_H
