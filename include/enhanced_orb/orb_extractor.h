// ORB with the truncated adaptive threshold, stage after stage: the enhancement (enhance.h), the
// pyramid (pyramid.h), per-cell thresholds (adaptive_threshold.h) and FAST corners (corners.h), the
// budget's selection (selection.h), orientation by intensity centroid (orientation.h) and rBRIEF
// descriptors interchangeable with cv::ORB's (rbrief.h).
#ifndef ENHANCED_ORB_ORB_EXTRACTOR_H
#define ENHANCED_ORB_ORB_EXTRACTOR_H

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/corners.h"
#include "enhanced_orb/orientation.h"
#include "enhanced_orb/params.h"
#include "enhanced_orb/pyramid.h"
#include "enhanced_orb/rbrief.h"
#include "enhanced_orb/selection.h"

namespace enhanced_orb {

// The largest image the nodelets and the tools take, 32 Mpixel (about 6000 x 5600): a larger one
// is refused with a message, not processed. The library itself takes any size.
constexpr std::int64_t kMaxImagePixels = 32LL << 20;

// Time of each stage of one extraction, in milliseconds. With threads > 1 the levels' stages run
// side by side: each stage is then its time summed over the levels, and extract_ms (wall clock)
// is less than their sum.
struct StageTimings {
  double convert_ms = 0.0;  // the caller's input turned to 8-bit gray (adapters, nodelets; 0 for gray)
  double judge_ms = 0.0;    // the camera-motion judgment before the extraction (a stream's frames only)
  double enhance_ms = 0.0;
  double pyramid_ms = 0.0;
  double threshold_ms = 0.0;
  double fast_ms = 0.0;
  double select_ms = 0.0;
  double orientation_ms = 0.0;
  double descriptor_ms = 0.0;  // smoothing and rBRIEF
  double extract_ms = 0.0;     // wall clock of everything after the enhancement
  double overlap_ms = 0.0;     // the judgment and the enhancement side by side (two threads), in both

  double extractMs() const { return extract_ms; }
  // The whole call: conversion, judgment, enhancement and extraction.
  double totalMs() const { return convert_ms + judge_ms + enhance_ms - overlap_ms + extract_ms; }
};

struct Extraction {
  std::vector<cv::KeyPoint> keypoints;    // level-0 coordinates; size, angle (degrees), response, octave
  cv::Mat descriptors;                    // keypoints.size() x kDescriptorBytes, CV_8U
  cv::Mat cell_thresholds;                // grid_size x grid_size CV_32S, level 0
  std::vector<cv::Mat> level_thresholds;  // the same for every pyramid level
  cv::Mat image;                          // the 8-bit image features were extracted from (enhanced or input)
  double lambda = 0.0;                    // eq 7 of the input (0 when enhancement is off)
  bool poor_quality = false;
  bool inverted = false;
  double noise = 0.0;            // estimateNoise() of `image` where noise_floor uses it, else 0
  bool camera_moving = false;    // the frame got the moving camera's selection (Params::movingSelection)
  std::vector<cv::Mat> pyramid;  // with ExtractOptions::keep_pyramid: each level's image (level 0 = image)
  StageTimings timings;
};

// What an extraction takes besides the image.
struct ExtractOptions {
  // Empty, or CV_8UC1 of the image's size: no keypoint where it is 0 (at the keypoint's level-0
  // position); such corners are left out before the budget's selection, so they take none of it.
  cv::Mat mask;
  // Copy each pyramid level into Extraction::pyramid (into its own buffers, reused from call to call).
  bool keep_pyramid = false;
  // With camera_motion auto: the frame's camera is judged moving (by a CameraMotion fed the
  // stream's frames in order), and the frame gets the moving camera's selection. A single image,
  // or the first frame of a stream, is judged still.
  bool camera_moving = false;
  // The stream's lambda for the tone curve's quality test of a moving camera's frame
  // (CameraMotion::streamLambda(), Params::forFrame); < 0: the frame's own.
  double stream_lambda = -1.0;
};

class OrbExtractor {
public:
  // Throws std::invalid_argument, with every offending parameter named, when `params` is invalid.
  explicit OrbExtractor(const Params& params = Params());

  const Params& params() const { return params_; }
  // Whether extract() reads the stream's judgment in ExtractOptions (Params::judgesStream():
  // camera_moving under camera_motion auto, stream_lambda where a moving camera's frame takes
  // moving_gamma_mode auto), so that a caller feeding a stream knows to judge its frames.
  bool judgesMotion() const { return params_.judgesStream(); }

  // Extracts from an 8-bit gray image. An empty image gives an empty result.
  // Throws std::invalid_argument when `gray` is not CV_8UC1.
  Extraction extract(const cv::Mat& gray) const;

  // The same into `out`, reusing its buffers: in a loop over frames of one size nothing is
  // allocated once the first frame is done. A result the caller keeps (a copy of `out`, or of one
  // of its matrices, made before the call) keeps its values: a buffer shared with it is let go
  // and a new one allocated instead of being overwritten.
  //
  // An extractor keeps a workspace (pyramid, score maps, histograms, keypoint lists) per
  // concurrent call and reuses it: calls from several threads at once are safe and get the
  // results of sequential calls; copies of an extractor share its workspaces.
  void extract(const cv::Mat& gray, Extraction& out) const;

  // The same with a mask and, on request, the pyramid. Throws std::invalid_argument when the mask
  // is neither empty nor CV_8UC1 of gray's size.
  void extract(const cv::Mat& gray, const ExtractOptions& options, Extraction& out) const;

  // A stream's next frame: judged by `motion` (fed the stream's frames in order) when the
  // extractor judgesMotion(), which sets options.camera_moving and options.stream_lambda, then
  // extracted; the judgment's time is out.timings.judge_ms. With two threads or more the frame is
  // enhanced while it is judged (out.timings.overlap_ms), with the same result. What every consumer
  // of a stream (the adapters, the tools, the benchmark) calls.
  void extract(const cv::Mat& gray, CameraMotion& motion, ExtractOptions& options, Extraction& out) const;

  // The descriptors of given keypoints (level-0 coordinates, `octave` naming the level, `angle` in
  // degrees, as extract() gives them) on the same enhanced and smoothed pyramid as extract(), in
  // their order. Keypoints that cannot be described (octave outside the pyramid, or closer than
  // kEdgeThreshold to their level's border) are removed, as cv::ORB removes them.
  void describe(const cv::Mat& gray, std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors) const;

  struct Workspace;

private:
  // A workspace from the pool, returned to it when the pointer goes.
  std::unique_ptr<Workspace, std::function<void(Workspace*)>> lease() const;
  std::unique_ptr<Workspace> acquire() const;
  // Everything after the enhancement (out.image), with the frame's parameters.
  void extractEnhanced(const Params& params, const ExtractOptions& options, Workspace& ws, Extraction& out) const;
  void release(std::unique_ptr<Workspace> ws) const;

  Params params_;
  struct Pool;
  std::shared_ptr<Pool> pool_;
};

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_ORB_EXTRACTOR_H
