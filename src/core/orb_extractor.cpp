#include "enhanced_orb/orb_extractor.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>

#include "enhanced_orb/adaptive_threshold.h"
#include "enhanced_orb/enhance.h"
#include "enhanced_orb/noise.h"
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
    StageTimings timings;
  };
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

// Runs work(level) for levels 0..n-1 on up to `threads` threads: each takes the next level not yet
// taken (the largest first) until none is left, so that no thread waits on another's share.
// Exceptions are passed on to the caller.
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
  std::exception_ptr failure;
  std::mutex failure_mutex;
  cv::parallel_for_(
      cv::Range(0, count),
      [&](const cv::Range& range) {
        for (int s = range.start; s < range.end; ++s) {
          try {
            for (int level = next++; level < n; level = next++) {
              work(level);
            }
          } catch (...) {
            std::lock_guard<std::mutex> lock(failure_mutex);
            failure = std::current_exception();
          }
        }
      },
      count);
  if (failure) {
    std::rethrow_exception(failure);
  }
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
void enhanceInto(const cv::Mat& gray, const Params& params, Extraction& out) {
  out.lambda = 0.0;
  out.poor_quality = false;
  out.inverted = false;
  if (!params.enhance_enabled) {
    out.image = gray;
    return;
  }
  ownOrRelease(out.image);
  const EnhanceResult enhanced = enhance(gray, params.enhance, out.image, params.orb.threads);
  out.image = enhanced.image;
  out.lambda = enhanced.lambda;
  out.poor_quality = enhanced.poor_quality;
  out.inverted = enhanced.inverted;
}

// Per level: the level itself, its cell thresholds (adaptive_threshold.h, or the fixed one), its
// corners and cv::ORB's smoothing for the descriptors. An empty image has one empty level: its
// thresholds are the grid's, its corners none.
void detectLevels(const Params& params, OrbExtractor::Workspace& ws, Extraction& out) {
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
    detectCorners(image, thresholds, l.corners, ws.keypoints[level]);
    l.timings.fast_ms = clock.lap();
    if (!ws.keypoints[level].empty()) {
      smoothForDescription(image, l.smoothing, l.smoothed);
    }
    l.timings.descriptor_ms = clock.lap();
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
  if (!gray.empty() && gray.type() != CV_8UC1) {
    throw std::invalid_argument("extract: expected CV_8UC1, got " + cv::typeToString(gray.type()));
  }
  const OrbParams& orb = params_.orb;
  out.timings = StageTimings();
  out.keypoints.clear();
  Stopwatch clock;
  enhanceInto(gray, params_, out);
  out.timings.enhance_ms = clock.lap();
  Stopwatch wall;
  std::unique_ptr<Workspace> ws = acquire();
  struct ReturnToPool {
    const OrbExtractor* self;
    std::unique_ptr<Workspace>& ws;
    ~ReturnToPool() {
      ws->pyramid.releaseInput();  // level 0 may be the caller's image: not kept alive by the pool
      self->release(std::move(ws));
    }
  } return_to_pool{this, ws};

  ws->pyramid.reset(out.image, orb.n_levels, orb.scale_factor);
  detectLevels(params_, *ws, out);
  clock.lap();
  out.noise = orb.max_features > 0 && orb.noise_floor > 0.0 ? estimateNoise(out.image) : 0.0;
  if (orb.max_features > 0) {
    selectByBudget(orb, out.noise, ws->pyramid.sizes(), ws->keypoints, ws->selection);
  }
  out.timings.select_ms = clock.lap();
  describeLevels(orb, *ws, out);
  addLevelTimings(*ws, ws->pyramid.count(), out.timings);
  out.timings.extract_ms = wall.lap();
}

}  // namespace enhanced_orb
