#include "enhanced_orb/orb_extractor.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <functional>
#include <mutex>
#include <stdexcept>
#include <string>

#include "enhanced_orb/adaptive_threshold.h"
#include "enhanced_orb/enhance.h"
#include "enhanced_orb/noise.h"
#include "parallel.h"
#include "pyramid_levels.h"
#include "stopwatch.h"

namespace enhanced_orb {

// Everything one extraction works in, kept from call to call (one scheme for every buffer: the
// extractor's pool hands a workspace to each concurrent call).
struct OrbExtractor::Workspace {
  struct Level {
    ThresholdWorkspace threshold;
    CornerWorkspace corners;
    SmoothingBuffers smoothing;
    cv::Mat smoothed;
    bool smoothed_ready = false;  // `smoothed` is this frame's
    cv::Mat raised;               // the cell thresholds raised to the noise floor
    StageTimings timings;
  };
  EnhanceWorkspace enhancement;
  PyramidLevels pyramid;
  std::vector<Level> levels;
  std::vector<std::vector<cv::KeyPoint>> keypoints;  // per level, in level coordinates
  SelectionWorkspace selection;
  std::vector<int> first;  // per level, its first row of the descriptors
};

struct OrbExtractor::Pool {
  std::mutex mutex;
  std::vector<std::unique_ptr<Workspace>> free;
};

OrbExtractor::OrbExtractor(const Params& params) : params_(params), pool_(std::make_shared<Pool>()) {
  const std::vector<std::string> problems = validate(params_);
  if (!problems.empty()) {
    throw std::invalid_argument(joinMessages(problems));
  }
  orbTests();  // read cv::ORB's tests now rather than in the first frame
}

std::unique_ptr<OrbExtractor::Workspace> OrbExtractor::acquire() const {
  {
    std::lock_guard<std::mutex> lock(pool_->mutex);
    if (!pool_->free.empty()) {
      std::unique_ptr<Workspace> ws = std::move(pool_->free.back());
      pool_->free.pop_back();
      return ws;
    }
  }
  return std::make_unique<Workspace>();
}

void OrbExtractor::release(std::unique_ptr<Workspace> ws) const {
  std::lock_guard<std::mutex> lock(pool_->mutex);
  pool_->free.push_back(std::move(ws));
}

namespace {

// Runs work(level) for levels (or any tasks) 0..n-1 on up to `threads` threads: each takes the
// next level not yet taken (the largest first) until none is left, so that no thread waits on
// another's share. Exceptions reach the caller (parallelFor).
template <typename Work>
void forEachLevel(int n, int threads, Work work) {
  const int count = std::min(threads, n);
  if (count <= 1) {
    for (int level = 0; level < n; ++level) {
      work(level);
    }
    return;
  }
  std::atomic<int> next{0};
  parallelFor(count, [&](const cv::Range&) {
    for (int level = next++; level < n; level = next++) {
      work(level);
    }
  });
}

}  // namespace

namespace {

// A buffer the caller may still share (a result kept from an earlier call) is let go instead of
// being overwritten.
void ownOrRelease(cv::Mat& m) {
  if (!(m.u && m.u->refcount == 1)) {
    m.release();
  }
}

// The enhancement (enhance.h) of `gray` into out.image, or `gray` itself when it is off.
void enhanceInto(const cv::Mat& gray, const Params& params, EnhanceWorkspace& ws, Extraction& out) {
  out.lambda = 0.0;
  out.poor_quality = false;
  out.inverted = false;
  if (!params.enhance_enabled) {
    out.image = gray;
    return;
  }
  ownOrRelease(out.image);
  const EnhanceResult enhanced = enhance(gray, params.enhance, ws, out.image);
  out.image = enhanced.image;
  out.lambda = enhanced.lambda;
  out.poor_quality = enhanced.poor_quality;
  out.inverted = enhanced.inverted;
}

// Drops the corners of `level` whose level-0 position is 0 in `mask`.
void applyMask(const cv::Mat& mask, float scale, std::vector<cv::KeyPoint>& corners) {
  corners.erase(std::remove_if(corners.begin(), corners.end(),
                               [&](const cv::KeyPoint& kp) {
                                 const int x = std::min(cvRound(kp.pt.x * scale), mask.cols - 1);
                                 const int y = std::min(cvRound(kp.pt.y * scale), mask.rows - 1);
                                 return mask.at<std::uint8_t>(y, x) == 0;
                               }),
                corners.end());
}

// The corners of `level` at its cell thresholds, each raised to at least `least` (0: as they are),
// those the mask allows; and cv::ORB's smoothing for the descriptors once the level has corners.
void detectLevel(const Params& params, const cv::Mat& mask, int level, int least, OrbExtractor::Workspace& ws,
                 Extraction& out) {
  OrbExtractor::Workspace::Level& l = ws.levels[level];
  const cv::Mat& image = ws.pyramid.built(level);
  const cv::Mat& thresholds = out.level_thresholds[level];
  const cv::Mat* used = &thresholds;
  if (least > 0) {
    l.raised.create(thresholds.size(), CV_32S);
    for (int i = 0; i < static_cast<int>(thresholds.total()); ++i) {
      l.raised.ptr<int>()[i] = std::max(thresholds.ptr<int>()[i], least);
    }
    used = &l.raised;
  }
  Stopwatch clock;
  detectCorners(image, *used, l.corners, ws.keypoints[level]);
  if (!mask.empty()) {
    applyMask(mask, levelScale(params.orb.scale_factor, level), ws.keypoints[level]);
  }
  l.timings.fast_ms += clock.lap();
  if (!ws.keypoints[level].empty() && !l.smoothed_ready) {
    smoothForDescription(image, l.smoothing, l.smoothed);
    l.smoothed_ready = true;
  }
  l.timings.descriptor_ms += clock.lap();
}

// Per level: the level itself, its cell thresholds (adaptive_threshold.h, or the fixed one) and
// detectLevel() at `least`. An empty image has one empty level: its thresholds are the grid's, its
// corners none.
void detectLevels(const Params& params, const cv::Mat& mask, int least, OrbExtractor::Workspace& ws, Extraction& out) {
  const int n_levels = ws.pyramid.count();
  ws.levels.resize(std::max(ws.levels.size(), static_cast<size_t>(n_levels)));
  ws.keypoints.resize(std::max(ws.keypoints.size(), static_cast<size_t>(n_levels)));
  out.cell_thresholds.release();  // level 0's thresholds again below
  out.level_thresholds.resize(static_cast<size_t>(n_levels));
  for (cv::Mat& t : out.level_thresholds) {
    ownOrRelease(t);
  }
  forEachLevel(n_levels, params.orb.threads, [&](int level) {
    OrbExtractor::Workspace::Level& l = ws.levels[level];
    l.timings = StageTimings();
    l.smoothed_ready = false;
    const cv::Mat& image = ws.pyramid.level(level, l.timings.pyramid_ms);
    Stopwatch clock;
    cv::Mat& thresholds = out.level_thresholds[level];
    if (params.orb.threshold_mode == ThresholdMode::kAdaptive) {
      cellThresholds(image, params.threshold, l.threshold, thresholds);
    } else {
      thresholds.create(params.threshold.grid_size, params.threshold.grid_size, CV_32S);
      thresholds.setTo(cv::Scalar(params.orb.fast_threshold));
    }
    l.timings.threshold_ms = clock.lap();
    detectLevel(params, mask, level, least, ws, out);
  });
  out.cell_thresholds = out.level_thresholds.front();
}

// Per level: the orientation and the descriptors of its selected corners, into the level's rows,
// and the keypoints in level-0 coordinates with their size and octave.
void describeLevels(const OrbParams& orb, OrbExtractor::Workspace& ws, Extraction& out) {
  const int n_levels = ws.pyramid.count();
  std::vector<int>& first = ws.first;
  first.assign(n_levels + 1, 0);
  for (int level = 0; level < n_levels; ++level) {
    first[level + 1] = first[level] + static_cast<int>(ws.keypoints[level].size());
  }
  ownOrRelease(out.descriptors);
  out.descriptors.create(first[n_levels], kDescriptorBytes, CV_8U);
  out.keypoints.resize(static_cast<size_t>(first[n_levels]));
  forEachLevel(n_levels, orb.threads, [&](int level) {
    std::vector<cv::KeyPoint>& keypoints = ws.keypoints[level];
    if (keypoints.empty()) {
      return;
    }
    StageTimings& timings = ws.levels[level].timings;
    Stopwatch clock;
    computeOrientation(ws.pyramid.built(level), keypoints);
    timings.orientation_ms = clock.lap();
    describe(ws.levels[level].smoothed, keypoints, out.descriptors, first[level]);
    const float scale = levelScale(orb.scale_factor, level);
    for (size_t i = 0; i < keypoints.size(); ++i) {
      cv::KeyPoint kp = keypoints[i];
      kp.pt *= scale;
      kp.size = kPatchSize * scale;
      kp.octave = level;
      out.keypoints[first[level] + i] = kp;
    }
    timings.descriptor_ms += clock.lap();
  });
}

// Each level's image into out.pyramid (level 0 is out.image itself), or none.
void keepPyramid(bool keep, const PyramidLevels& pyramid, Extraction& out) {
  out.pyramid.resize(keep ? static_cast<size_t>(pyramid.count()) : 0);
  for (size_t level = 0; level < out.pyramid.size(); ++level) {
    if (level == 0) {
      out.pyramid[0] = out.image;
    } else {
      ownOrRelease(out.pyramid[level]);
      pyramid.built(static_cast<int>(level)).copyTo(out.pyramid[level]);
    }
  }
}

void checkInput(const cv::Mat& gray, const cv::Mat& mask) {
  if (!gray.empty() && gray.type() != CV_8UC1) {
    throw std::invalid_argument("extract: expected CV_8UC1, got " + cv::typeToString(gray.type()));
  }
  if (!mask.empty() && (mask.type() != CV_8UC1 || mask.size() != gray.size())) {
    throw std::invalid_argument("extract: the mask must be CV_8UC1 of the image's size (" + std::to_string(gray.cols) +
                                "x" + std::to_string(gray.rows) + "), got " + cv::typeToString(mask.type()) + " " +
                                std::to_string(mask.cols) + "x" + std::to_string(mask.rows));
  }
}

// The levels' stage times summed into `timings` (the levels may have run side by side).
void addLevelTimings(const OrbExtractor::Workspace& ws, int n_levels, StageTimings& timings) {
  for (int level = 0; level < n_levels; ++level) {
    const StageTimings& t = ws.levels[level].timings;
    timings.pyramid_ms += t.pyramid_ms;
    timings.threshold_ms += t.threshold_ms;
    timings.fast_ms += t.fast_ms;
    timings.orientation_ms += t.orientation_ms;
    timings.descriptor_ms += t.descriptor_ms;
  }
}

}  // namespace

Extraction OrbExtractor::extract(const cv::Mat& gray) const {
  Extraction out;
  extract(gray, out);
  return out;
}

void OrbExtractor::extract(const cv::Mat& gray, Extraction& out) const {
  extract(gray, ExtractOptions(), out);
}

std::unique_ptr<OrbExtractor::Workspace, std::function<void(OrbExtractor::Workspace*)>> OrbExtractor::lease() const {
  return {acquire().release(), [this](Workspace* ws) {
            ws->pyramid.releaseInput();  // level 0 may be the caller's image: not kept alive by the pool
            release(std::unique_ptr<Workspace>(ws));
          }};
}

void OrbExtractor::extract(const cv::Mat& gray, const ExtractOptions& options, Extraction& out) const {
  checkInput(gray, options.mask);
  const Params params = params_.forFrame(options.camera_moving, options.stream_lambda);
  out.timings = StageTimings();
  const auto ws = lease();
  Stopwatch clock;
  enhanceInto(gray, params, ws->enhancement, out);
  out.timings.enhance_ms = clock.lap();
  extractEnhanced(params, options, *ws, out);
}

void OrbExtractor::extractEnhanced(const Params& params, const ExtractOptions& options, Workspace& ws,
                                   Extraction& out) const {
  out.camera_moving = params_.movingSelection(options.camera_moving);
  out.keypoints.clear();
  const OrbParams& orb = params.orb;
  Stopwatch clock;
  Stopwatch wall;
  // With a noise floor, each level's budget is spread over its corners scoring at least the floor:
  // they are found with every cell's FAST threshold raised to it (FAST keeps a score above its
  // threshold), which gives the same corners with the same scores, since a neighbour that would
  // suppress one of them scores higher still. A level with fewer than its budget above the floor
  // is searched again at its own thresholds (selectByBudget's `complete`).
  const bool by_floor = orb.max_features > 0 && orb.noise_floor > 0.0;
  out.noise = by_floor ? estimateNoise(out.image) : 0.0;
  const int least = by_floor ? std::clamp(static_cast<int>(std::ceil(orb.noise_floor * out.noise)) - 1, 0, 255) : 0;
  const double select_ms = clock.lap();  // the noise estimate, part of the selection
  ws.pyramid.reset(out.image, orb.n_levels, orb.scale_factor);
  detectLevels(params, options.mask, least, ws, out);
  clock.lap();
  if (orb.max_features > 0) {
    // One reference captured: std::function keeps it without a heap allocation.
    const auto redetect = [&](int level) { detectLevel(params, options.mask, level, 0, ws, out); };
    const auto complete = [&redetect](size_t level) { redetect(static_cast<int>(level)); };
    selectByBudget(orb, out.noise, ws.pyramid.sizes(), ws.keypoints, ws.selection,
                   least > 0 ? std::function<void(size_t)>(complete) : nullptr);
  }
  out.timings.select_ms = select_ms + clock.lap();
  describeLevels(orb, ws, out);
  keepPyramid(options.keep_pyramid, ws.pyramid, out);
  addLevelTimings(ws, ws.pyramid.count(), out.timings);
  out.timings.extract_ms = wall.lap();
}

void OrbExtractor::extract(const cv::Mat& gray, CameraMotion& motion, ExtractOptions& options, Extraction& out) const {
  if (params_.orb.threads < 2 || !judgesMotion() || gray.empty()) {
    Stopwatch clock;
    const StreamJudgment stream = judgesMotion() ? motion.judge(gray) : StreamJudgment();
    options.camera_moving = stream.moving;
    options.stream_lambda = stream.stream_lambda;
    const double judge_ms = clock.lap();
    extract(gray, options, out);
    out.timings.judge_ms = judge_ms;
    return;
  }
  // Two threads: the frame is judged on one while the other enhances it as the last frame's
  // judgment would have it (which the frame's own judgment nearly always repeats). Only the
  // enhancement's quality test hangs on the judgment (Params::forFrame() sets its gamma_mode): where
  // the frame's judgment decides the test otherwise, the frame is enhanced again.
  checkInput(gray, options.mask);
  const Params guess = params_.forFrame(motion.moving(), motion.streamLambda());
  out.timings = StageTimings();
  const auto ws = lease();
  StreamJudgment stream;
  double judge_ms = 0.0;
  double enhance_ms = 0.0;
  Stopwatch wall;
  forEachLevel(2, 2, [&](int task) {
    Stopwatch clock;
    if (task == 0) {
      stream = motion.judge(gray);
      judge_ms = clock.lap();
    } else {
      enhanceInto(gray, guess, ws->enhancement, out);
      enhance_ms = clock.lap();
    }
  });
  out.timings.overlap_ms = std::max(0.0, judge_ms + enhance_ms - wall.lap());
  options.camera_moving = stream.moving;
  options.stream_lambda = stream.stream_lambda;
  const Params params = params_.forFrame(stream.moving, stream.stream_lambda);
  if (params.enhance_enabled && isPoorQuality(out.lambda, params.enhance) != out.poor_quality) {
    enhanceInto(gray, params, ws->enhancement, out);
    enhance_ms += wall.lap();
  }
  out.timings.judge_ms = judge_ms;
  out.timings.enhance_ms = enhance_ms;
  extractEnhanced(params, options, *ws, out);
}

void OrbExtractor::describe(const cv::Mat& gray, std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors) const {
  checkInput(gray, cv::Mat());
  const auto ws = lease();
  Extraction enhanced;
  enhanceInto(gray, params_, ws->enhancement, enhanced);
  ws->pyramid.reset(enhanced.image, params_.orb.n_levels, params_.orb.scale_factor);
  const int n_levels = gray.empty() ? 0 : ws->pyramid.count();
  // The describable keypoints level by level (in their order within a level), in level coordinates.
  ws->keypoints.resize(std::max(ws->keypoints.size(), static_cast<size_t>(n_levels)));
  ws->levels.resize(std::max(ws->levels.size(), static_cast<size_t>(n_levels)));
  std::vector<std::vector<cv::KeyPoint>> given(static_cast<size_t>(n_levels));
  for (int level = 0; level < n_levels; ++level) {
    ws->keypoints[level].clear();
  }
  for (const cv::KeyPoint& kp : keypoints) {
    if (kp.octave < 0 || kp.octave >= n_levels) {
      continue;
    }
    const float scale = levelScale(params_.orb.scale_factor, kp.octave);
    const cv::Size size = ws->pyramid.sizes()[kp.octave];
    cv::KeyPoint at_level = kp;
    at_level.pt /= scale;
    const cv::Point c(cvRound(at_level.pt.x), cvRound(at_level.pt.y));
    if (c.x >= kEdgeThreshold && c.y >= kEdgeThreshold && c.x < size.width - kEdgeThreshold &&
        c.y < size.height - kEdgeThreshold) {
      ws->keypoints[kp.octave].push_back(at_level);
      given[kp.octave].push_back(kp);
    }
  }
  keypoints.clear();
  for (const std::vector<cv::KeyPoint>& level : given) {
    keypoints.insert(keypoints.end(), level.begin(), level.end());
  }
  descriptors.create(static_cast<int>(keypoints.size()), kDescriptorBytes, CV_8U);
  int row = 0;
  for (int level = 0; level < n_levels; ++level) {
    if (ws->keypoints[level].empty()) {
      continue;
    }
    double ms = 0.0;
    Workspace::Level& l = ws->levels[level];
    smoothForDescription(ws->pyramid.level(level, ms), l.smoothing, l.smoothed);
    enhanced_orb::describe(l.smoothed, ws->keypoints[level], descriptors, row);
    row += static_cast<int>(ws->keypoints[level].size());
  }
}

}  // namespace enhanced_orb
