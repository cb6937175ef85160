// enhanced_orb as a cv::Feature2D: code written for cv::ORB (detect, compute, detectAndCompute,
// matchers, drawKeypoints, FileStorage) runs on it with only the type changed.
//
//   cv::Ptr<cv::Feature2D> orb = enhanced_orb::ORB::create();   // was cv::ORB::create()
//   orb->detectAndCompute(image, mask, keypoints, descriptors);
#ifndef ENHANCED_ORB_FEATURE2D_H
#define ENHANCED_ORB_FEATURE2D_H

#include <memory>
#include <string>
#include <vector>

#include <opencv2/features2d.hpp>

#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/orb_extractor.h"
#include "enhanced_orb/params.h"

namespace enhanced_orb {

// A preset by name: "default", "paper", "stretch", "motion" or "baseline"; std::invalid_argument
// otherwise.
Params presetParams(const std::string& name);

// Parameters from a FileStorage node: a `preset` name, if any, seeds them (else `base`), then each
// parameter present by its ROS name (paramNames()); other keys are ignored, so the package's
// config/*.yaml files read as they are. Throws std::invalid_argument on a bad value or range.
// `given`, where not null, receives the names of the parameters the node sets, in paramNames()'s
// order.
Params readParams(const cv::FileNode& node, const Params& base = Params(), std::vector<std::string>* given = nullptr);
// The same from a YAML file (the `%YAML:1.0` line OpenCV wants may be missing, as in ROS files).
Params readParamsFile(const std::string& path, const Params& base = Params(),
                      std::vector<std::string>* given = nullptr);

class ORB : public cv::Feature2D {
public:
  // Throws std::invalid_argument, naming every offending parameter, when `params` is invalid.
  static cv::Ptr<ORB> create(const Params& params = Params());
  static cv::Ptr<ORB> create(const std::string& preset);  // presetParams(preset)

  const Params& params() const { return extractor_.params(); }
  void setParams(const Params& params);  // validated as create() does

  // 8-bit gray or BGR/BGRA input (anything else: cv::Exception, as cv::ORB). Without provided
  // keypoints: OrbExtractor::extract(), no keypoint where the 8-bit mask (empty, or the image's
  // size) is 0. With them (compute()): OrbExtractor::describe(), the keypoints that cannot be
  // described removed. The images detected on are taken as one camera's frames in order: with
  // camera_motion auto (the default) they decide whether the camera is judged moving
  // (CameraMotion). For images that are not one stream, call clear() before each, or use
  // camera_motion still.

  void detectAndCompute(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                        cv::OutputArray descriptors, bool useProvidedKeypoints = false) override;

  int descriptorSize() const override { return kDescriptorBytes; }
  int descriptorType() const override { return CV_8U; }
  int defaultNorm() const override { return cv::NORM_HAMMING; }
  cv::String getDefaultName() const override { return "Feature2D.EnhancedORB"; }
  bool empty() const override { return false; }
  // Forgets the stream of images seen so far: the next image is judged as a new stream's first.
  void clear() override;
  // Whether the last image detected on got the moving camera's selection (Extraction::camera_moving).
  bool cameraMoving() const { return result_.camera_moving; }
  // The last detect/detectAndCompute's times, the whole call: conversion to gray, judgment,
  // enhancement, extraction (StageTimings::totalMs()).
  const StageTimings& timings() const { return result_.timings; }

  // The parameters by their ROS names (as setParam() reads them); read() is readParams() starting
  // from the current ones.
  void write(cv::FileStorage& fs) const override;
  void read(const cv::FileNode& node) override;

private:
  explicit ORB(const Params& params) : extractor_(params) {}

  OrbExtractor extractor_;
  CameraMotion motion_;
  Extraction result_;  // reused from call to call
};

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_FEATURE2D_H
