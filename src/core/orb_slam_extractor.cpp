#include "enhanced_orb/orb_slam_extractor.h"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/feature2d.h"
#include "enhanced_orb/orb_extractor.h"
#include "stopwatch.h"

namespace enhanced_orb {
namespace {

// A SLAM map matches each frame against points described from frames under earlier light, so in
// ORB-SLAM a moving camera's frames all get the tone curve, whatever their quality test says: through
// a dip of the light ORB-SLAM3 then keeps tracking in one map, where the quality test's choice (auto)
// and no curve (never, what relative pose between nearby frames prefers) lose it (docs/ORB_SLAM3.md,
// "What the two SLAM choices buy").
constexpr GammaMode kSlamMovingGammaMode = GammaMode::kAlways;

// The five-argument constructor's other parameters: the file ENHANCED_ORB_CONFIG names, or the
// default mode; moving_gamma_mode kSlamMovingGammaMode unless the file sets it.
Params configuredBase() {
  const char* path = std::getenv("ENHANCED_ORB_CONFIG");
  std::vector<std::string> given;
  Params params = path && *path ? readParamsFile(path, Params(), &given) : Params();
  if (std::find(given.begin(), given.end(), "moving_gamma_mode") == given.end()) {
    params.enhance.moving_gamma_mode = kSlamMovingGammaMode;
  }
  return params;
}

Params withOrbSlamSettings(Params params, int nfeatures, float scaleFactor, int nlevels, int iniThFAST, int minThFAST) {
  params.orb.max_features = nfeatures;
  params.orb.scale_factor = scaleFactor;
  params.orb.n_levels = nlevels;
  params.orb.fast_threshold = iniThFAST;
  params.threshold.c_min = minThFAST;
  return params;
}

}  // namespace

struct OrbSlamExtractor::State {
  OrbExtractor extractor;
  Extraction result;
  cv::Mat ordered;  // the descriptors in ORB-SLAM3's order, reused frame after frame
  // ORB-SLAM calls each extractor with one camera's frames in order, and its map starts from the
  // first ones of a moving camera.
  CameraMotion motion{CameraMotion::Start::kMoving};
};

OrbSlamExtractor::OrbSlamExtractor(int nfeatures, float scaleFactor, int nlevels, int iniThFAST, int minThFAST)
    : OrbSlamExtractor(nfeatures, scaleFactor, nlevels, iniThFAST, minThFAST, configuredBase()) {}

OrbSlamExtractor::OrbSlamExtractor(int nfeatures, float scaleFactor, int nlevels, int iniThFAST, int minThFAST,
                                   const Params& base)
    : state_(new State{OrbExtractor(withOrbSlamSettings(base, nfeatures, scaleFactor, nlevels, iniThFAST, minThFAST)),
                       Extraction(), cv::Mat()}),
      scale_factor_(scaleFactor) {
  const OrbParams& orb = state_->extractor.params().orb;
  for (int level = 0; level < orb.n_levels; ++level) {
    const float scale = levelScale(orb.scale_factor, level);
    mvScaleFactor.push_back(scale);
    mvInvScaleFactor.push_back(1.0f / scale);
    mvLevelSigma2.push_back(scale * scale);
    mvInvLevelSigma2.push_back(1.0f / (scale * scale));
  }
}

OrbSlamExtractor::~OrbSlamExtractor() = default;

const Params& OrbSlamExtractor::params() const {
  return state_->extractor.params();
}

int OrbSlamExtractor::operator()(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                                 cv::OutputArray descriptors, std::vector<int>& vLappingArea) {
  const cv::Mat input = image.getMat();
  if (input.empty()) {
    return -1;
  }
  Stopwatch clock;
  cv::Mat gray = input;
  if (input.type() == CV_8UC3) {
    cv::cvtColor(input, gray, cv::COLOR_BGR2GRAY);
  } else if (input.type() == CV_8UC4) {
    cv::cvtColor(input, gray, cv::COLOR_BGRA2GRAY);
  } else if (input.type() != CV_8UC1) {
    CV_Error(cv::Error::StsUnsupportedFormat,
             "OrbSlamExtractor: expected an 8-bit gray, BGR or BGRA image, got " + cv::typeToString(input.type()));
  }
  ExtractOptions options;
  options.mask = mask.getMat();
  options.keep_pyramid = true;
  const double convert_ms = clock.lap();
  Extraction& result = state_->result;
  state_->extractor.extract(gray, state_->motion, options, result);
  result.timings.convert_ms = convert_ms;
  std::swap(mvImagePyramid, result.pyramid);  // the previous levels' buffers are reused next time

  // ORB-SLAM3's order: keypoints outside the lapping area from the front, inside it from the back.
  const int n = static_cast<int>(result.keypoints.size());
  keypoints.resize(static_cast<size_t>(n));
  cv::Mat& ordered = state_->ordered;
  ordered.create(n, kDescriptorBytes, CV_8U);
  const bool lapping = vLappingArea.size() >= 2;
  int mono = 0;
  int stereo = n - 1;
  for (int i = 0; i < n; ++i) {
    const cv::KeyPoint& kp = result.keypoints[i];
    const bool inside = lapping && kp.pt.x >= vLappingArea[0] && kp.pt.x <= vLappingArea[1];
    const int row = inside ? stereo-- : mono++;
    keypoints[row] = kp;
    result.descriptors.row(i).copyTo(ordered.row(row));
  }
  if (descriptors.needed()) {
    ordered.copyTo(descriptors);
  }
  return mono;
}

void OrbSlamExtractor::operator()(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                                  cv::OutputArray descriptors) {
  std::vector<int> none;
  (*this)(image, mask, keypoints, descriptors, none);
}

}  // namespace enhanced_orb
