#include "enhanced_orb/evaluation/methods.h"

#include <chrono>
#include <memory>
#include <stdexcept>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/evaluation/orb_slam_style.h"
#include "enhanced_orb/orb_extractor.h"

namespace enhanced_orb {
namespace evaluation {
namespace {

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

std::vector<std::string> methodNames() {
  return {"default", "motion", "stretch", "paper", "baseline", "cv::ORB", "CLAHE+cv::ORB", "ORB-SLAM"};
}

Method makeMethod(const std::string& name, int budget, const Params& params) {
  Preset preset = Preset::kDefault;
  if (parsePreset(name, preset)) {
    // The default mode's parameters are the caller's; a named preset's its own.
    Params p = preset == Preset::kDefault ? params : Params::preset(preset);
    p.orb.max_features = budget;
    auto extractor = std::make_shared<const OrbExtractor>(p);
    return {name, budget, [extractor](const cv::Mat& gray, const StreamJudgment& stream) {
              const auto start = std::chrono::steady_clock::now();
              ExtractOptions options;
              options.camera_moving = stream.moving;
              options.stream_lambda = stream.stream_lambda;
              Extraction r;
              extractor->extract(gray, options, r);
              return Features{std::move(r.keypoints), r.descriptors, msSince(start)};
            }};
  }
  if (name == "cv::ORB" || name == "CLAHE+cv::ORB") {
    cv::Ptr<cv::ORB> orb = cv::ORB::create(budget > 0 ? budget : 1000000, 1.2f, 8);
    cv::Ptr<cv::CLAHE> clahe = name == "CLAHE+cv::ORB" ? cv::createCLAHE(3.0, cv::Size(8, 8)) : nullptr;
    return {name, budget, [orb, clahe](const cv::Mat& gray, const StreamJudgment&) {
              Features f;
              const auto start = std::chrono::steady_clock::now();
              cv::Mat input;  // a new buffer: CLAHE would write into a header of `gray` in place
              if (clahe) {
                clahe->apply(gray, input);
              } else {
                input = gray;
              }
              orb->detectAndCompute(input, cv::noArray(), f.keypoints, f.descriptors);
              f.ms = msSince(start);
              return f;
            }};
  }
  if (name == "ORB-SLAM") {
    OrbSlamStyleParams p;
    p.n_features = budget > 0 ? budget : 1000000;
    auto extractor = std::make_shared<const OrbSlamStyleExtractor>(p);
    return {name, budget, [extractor](const cv::Mat& gray, const StreamJudgment&) {
              Features f;
              const auto start = std::chrono::steady_clock::now();
              extractor->extract(gray, f.keypoints, f.descriptors);
              f.ms = msSince(start);
              return f;
            }};
  }
  throw std::invalid_argument("unknown method '" + name + "'");
}

}  // namespace evaluation
}  // namespace enhanced_orb
