// The extractors compared at equal budgets: this package's default mode, the paper preset, the
// original ORB (baseline), cv::ORB, CLAHE (3.0, 8x8) followed by cv::ORB, and ORB-SLAM's extractor.
#ifndef ENHANCED_ORB_EVALUATION_METHODS_H
#define ENHANCED_ORB_EVALUATION_METHODS_H

#include <functional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/params.h"

namespace enhanced_orb {
namespace evaluation {

struct Features {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  double ms = 0.0;  // wall-clock extraction time, enhancement included
};

struct Method {
  std::string name;
  int budget = 1000;  // 0: every corner
  // Extracts from one frame. `stream`: the frame's judgment (CameraMotion fed the stream's frames
  // in order, judgeMotion()); only modes with camera_motion auto read it. A single image: judged
  // still.
  std::function<Features(const cv::Mat& gray, const StreamJudgment& stream)> extract;

  Features run(const cv::Mat& gray, const StreamJudgment& stream = StreamJudgment()) const {
    return extract(gray, stream);
  }
};

// "default", "motion", "stretch", "paper", "baseline", "cv::ORB", "CLAHE+cv::ORB" (motion, stretch and
// paper: the presets)
// and "ORB-SLAM" (ORB-SLAM's extractor, orb_slam_style.h).
std::vector<std::string> methodNames();

// A method by name at a budget (cv::ORB asks for 10^6 features when budget is 0). `params` replaces
// the default mode's parameters (e.g. for an ablation); the budget is set on it.
// Throws std::invalid_argument for an unknown name.
Method makeMethod(const std::string& name, int budget, const Params& params = Params());

}  // namespace evaluation
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_EVALUATION_METHODS_H
