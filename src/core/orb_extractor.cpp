#include "enhanced_orb/orb_extractor.h"

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <mutex>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "enhanced_orb/adaptive_threshold.h"
#include "enhanced_orb/enhance.h"
#include "enhanced_orb/noise.h"
#include "enhanced_orb/rbrief.h"
#include "enhanced_orb/simd.h"
#include "kernels/fast_score.h"
#include "kernels/suppression.h"
#include "linear_resize.h"

namespace enhanced_orb {
namespace {

constexpr int kOrientationRadius = 15;

class Stopwatch {
public:
  // Milliseconds since the last call (or construction).
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double ms = std::chrono::duration<double, std::milli>(now - last_).count();
    last_ = now;
    return ms;
  }

private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// Half-widths of the rows of the circular patch: the pixels within r + 1/2 of the centre, a disc
// symmetric under every quarter turn and transposition (the same disc as cv::ORB's).
std::array<int, kOrientationRadius + 1> patchHalfWidths() {
  const double rim = (kOrientationRadius + 0.5) * (kOrientationRadius + 0.5);
  std::array<int, kOrientationRadius + 1> u_max{};
  for (int v = 0; v <= kOrientationRadius; ++v) {
    u_max[v] = static_cast<int>(std::floor(std::sqrt(rim - v * v)));
  }
  return u_max;
}

float levelScale(double scale_factor, int level) {
  return static_cast<float>(std::pow(scale_factor, level));
}

// Level sizes as buildPyramid() makes them; fewer than n_levels when a level would be empty.
void pyramidSizes(cv::Size size, int n_levels, double scale_factor, std::vector<cv::Size>& sizes) {
  sizes.assign(1, size);
  for (int level = 1; level < n_levels; ++level) {
    const float inv_scale = 1.0f / levelScale(scale_factor, level);
    const cv::Size next(cvRound(size.width * inv_scale), cvRound(size.height * inv_scale));
    if (next.width < 1 || next.height < 1) {
      break;
    }
    sizes.push_back(next);
  }
}

// Stronger response first; position breaks ties, so that every selection is deterministic.
bool stronger(const cv::KeyPoint& a, const cv::KeyPoint& b) {
  if (a.response != b.response) {
    return a.response > b.response;
  }
  return a.pt.y != b.pt.y ? a.pt.y < b.pt.y : a.pt.x < b.pt.x;
}

// A buffer the caller may still share is let go instead of being overwritten.
void ownOrRelease(cv::Mat& m) {
  if (!(m.u && m.u->refcount == 1)) {
    m.release();
  }
}

// The non-maximum suppression of detectCorners on one band of cells (one grid row), a whole
// interior row at a time. b (a corner's score, 0 for other pixels) is computed with each pixel's
// own cell threshold; a neighbour across a cell edge counts 0.
class BandSuppression {
public:
  // starts[0..cells]: the first column of each cell of the band and, last, the end of the interior.
  BandSuppression(const cv::Mat& scores, const int* starts, int cells, const int* thresholds,
                  std::vector<std::uint8_t>& buffer)
      : scores_(scores), x0_(starts[0]), cells_(cells), simd_(activeSimdLevel()) {
    width_ = starts[cells] - x0_;
    for (int c = 0; c <= cells; ++c) {
      starts_[c] = starts[c] - x0_;
    }
    for (int c = 0; c < cells; ++c) {
      thresholds_[c] = static_cast<std::uint8_t>(thresholds[c]);
    }
    const size_t row = static_cast<size_t>(width_) + 72;  // a zero column each side, 64-flag reads
    buffer.assign(7 * row, 0);
    for (int k = 0; k < 3; ++k) {
      b_[k] = buffer.data() + k * row + 1;
      around_[k] = buffer.data() + (3 + k) * row + 1;
    }
    keep_ = buffer.data() + 6 * row;
  }

  // Appends the corners of rows [y0, y1) of the band to each cell's list.
  void run(int y0, int y1, std::vector<std::vector<cv::KeyPoint>>& cell_corners) {
    clearRow(0);
    fillRow(y0, 1);
    for (int y = y0; y < y1; ++y) {
      if (y + 1 < y1) {
        fillRow(y + 1, 2);
      } else {
        clearRow(2);
      }
      const std::uint8_t* here = b_[1];
      kernels::suppressionKeep(simd_, here, around_[0], around_[2], starts_, cells_, keep_);
      // Few flags are set: gather them 64 at a time into a bit mask and visit its set bits.
      int cell = 0;
      for (int i = 0; i < width_; i += 64) {
        std::uint64_t mask = 0;
        for (int w = 0; w < 8; ++w) {
          std::uint64_t flags;  // eight 0/1 bytes (the buffer's tail is zero)
          std::memcpy(&flags, keep_ + i + 8 * w, sizeof flags);
          mask |= ((flags * 0x0102040810204080ULL) >> 56) << (8 * w);
        }
        while (mask != 0) {
          const int j = i + __builtin_ctzll(mask);
          mask &= mask - 1;
          while (j >= starts_[cell + 1]) {
            ++cell;
          }
          cell_corners[cell].emplace_back(static_cast<float>(x0_ + j), static_cast<float>(y), 7.0f, -1.0f,
                                          static_cast<float>(here[j]));
        }
      }
      std::rotate(b_, b_ + 1, b_ + 3);
      std::rotate(around_, around_ + 1, around_ + 3);
    }
  }

private:
  void clearRow(int slot) {
    std::memset(b_[slot] - 1, 0, width_ + 2);
    std::memset(around_[slot] - 1, 0, width_ + 2);
  }

  // Slot `slot` gets row y's b and the maximum of each b's three horizontal neighbours in its cell.
  void fillRow(int y, int slot) {
    kernels::suppressionRow(simd_, scores_.ptr<std::uint8_t>(y) + x0_, starts_, thresholds_, cells_, b_[slot],
                            around_[slot]);
  }

  const cv::Mat& scores_;
  int x0_;
  int cells_;
  SimdLevel simd_;
  int width_ = 0;
  int starts_[33];
  std::uint8_t thresholds_[32];
  std::uint8_t* b_[3];
  std::uint8_t* around_[3];
  std::uint8_t* keep_;
};

}  // namespace

std::vector<cv::Mat> buildPyramid(const cv::Mat& image, int n_levels, double scale_factor) {
  std::vector<cv::Mat> pyramid{image};
  std::vector<cv::Size> sizes;
  pyramidSizes(image.size(), n_levels, scale_factor, sizes);
  LinearResize resize;
  for (size_t level = 1; level < sizes.size(); ++level) {
    cv::Mat next;
    resize(pyramid.back(), next, sizes[level], activeSimdLevel());
    pyramid.push_back(next);
  }
  return pyramid;
}

void detectCorners(const cv::Mat& level, const cv::Mat& thresholds, CornerWorkspace& ws,
                   std::vector<cv::KeyPoint>& corners) {
  CV_Assert(level.type() == CV_8UC1 && thresholds.type() == CV_32S && thresholds.rows == thresholds.cols);
  corners.clear();
  const cv::Rect interior(kEdgeThreshold, kEdgeThreshold, level.cols - 2 * kEdgeThreshold,
                          level.rows - 2 * kEdgeThreshold);
  if (interior.width <= 0 || interior.height <= 0) {
    return;
  }
  const int grid = thresholds.rows;
  const kernels::FastScoreRowKernel score_row = kernels::fastScoreRowKernel(activeSimdLevel());
  ws.scores.create(level.size(), CV_8UC1);
  ws.floors.resize(static_cast<size_t>(interior.width));
  ws.cell_lists.resize(static_cast<size_t>(grid));
  int starts_data[33];
  int band_thresholds[32];
  for (int cy = 0; cy < grid; ++cy) {
    // The band's non-empty cells, left to right; gridCell's cells tile the level. cv::FAST clamps
    // its threshold to [0, 255].
    int cells = 0;
    cv::Rect rows;
    for (int cx = 0; cx < grid; ++cx) {
      const cv::Rect cell = gridCell(level.size(), grid, cx, cy) & interior;
      if (!cell.empty()) {
        starts_data[cells] = cell.x;
        band_thresholds[cells] = std::clamp(thresholds.at<int>(cy, cx), 0, 255);
        std::fill(ws.floors.begin() + (cell.x - interior.x), ws.floors.begin() + (cell.br().x - interior.x),
                  static_cast<std::uint8_t>(band_thresholds[cells]));
        ++cells;
        rows = cell;
      }
    }
    if (cells == 0) {
      continue;
    }
    starts_data[cells] = rows.br().x;
    // The band's FAST scores (only the interior of the map is written). A pixel scoring at or
    // below its cell's threshold can neither be a corner nor weigh in the suppression (which counts
    // neighbours of the same cell only), so the kernel may write 0 for it, and skip a vector of
    // such pixels.
    for (int y = rows.y; y < rows.br().y; ++y) {
      score_row(level.ptr<std::uint8_t>(y) + interior.x, static_cast<std::ptrdiff_t>(level.step), interior.width,
                ws.scores.ptr<std::uint8_t>(y) + interior.x, ws.floors.data());
    }
    // cv::FAST run on each cell's window (the cell widened by 3, where its circle reads) keeps a
    // corner when its score exceeds that of each of its 8 neighbours, a neighbour counting 0 unless
    // it lies in the cell and is a corner at the cell's threshold. With b = score for the cell's
    // corners and 0 elsewhere (in and around the cell), that is b above the largest b around it;
    // the band's rows are all it reads. Corners come cell by cell (row-major), each cell row by row.
    for (auto& list : ws.cell_lists) {
      list.clear();
    }
    BandSuppression(ws.scores, starts_data, cells, band_thresholds, ws.rows).run(rows.y, rows.br().y, ws.cell_lists);
    for (int c = 0; c < cells; ++c) {
      corners.insert(corners.end(), ws.cell_lists[c].begin(), ws.cell_lists[c].end());
    }
  }
}

std::vector<cv::KeyPoint> detectCorners(const cv::Mat& level, const cv::Mat& thresholds) {
  CornerWorkspace ws;
  std::vector<cv::KeyPoint> corners;
  detectCorners(level, thresholds, ws, corners);
  return corners;
}

namespace {

void levelBudgets(int total, int n_levels, double scale_factor, std::vector<int>& budgets) {
  budgets.assign(n_levels, 0);
  const double factor = 1.0 / scale_factor;
  double per_level = total * (1.0 - factor) / (1.0 - std::pow(factor, n_levels));
  int assigned = 0;
  for (int level = 0; level + 1 < n_levels; ++level) {
    budgets[level] = std::min(cvRound(per_level), total - assigned);
    assigned += budgets[level];
    per_level *= factor;
  }
  budgets[n_levels - 1] = total - assigned;
}

}  // namespace

std::vector<int> levelBudgets(int total, int n_levels, double scale_factor) {
  std::vector<int> budgets;
  levelBudgets(total, n_levels, scale_factor, budgets);
  return budgets;
}

namespace {

// The keys of keypoints whose responses are integers in [0, 65535] at integer positions in
// [0, 65535] (the extractor's corners): (65535 - response) << 32 | y << 16 | x, so that ascending
// keys are `stronger` order. False, with `keys` unspecified, for any other keypoint.
bool packedStrengthKeys(const std::vector<cv::KeyPoint>& keypoints, std::vector<std::uint64_t>& keys) {
  keys.resize(keypoints.size());
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const cv::KeyPoint& kp = keypoints[i];
    const float r = kp.response;
    if (!(r >= 0.0f && r <= 65535.0f && kp.pt.x >= 0.0f && kp.pt.x <= 65535.0f && kp.pt.y >= 0.0f &&
          kp.pt.y <= 65535.0f) ||
        r != std::floor(r) || kp.pt.x != std::floor(kp.pt.x) || kp.pt.y != std::floor(kp.pt.y)) {
      return false;
    }
    keys[i] = (static_cast<std::uint64_t>(65535 - static_cast<int>(r)) << 32) |
              (static_cast<std::uint64_t>(kp.pt.y) << 16) | static_cast<std::uint64_t>(kp.pt.x);
  }
  return true;
}

}  // namespace

void keepStrongest(std::vector<cv::KeyPoint>& keypoints, size_t n) {
  if (keypoints.size() <= n) {
    return;
  }
  if (n == 0) {
    keypoints.clear();
    return;
  }
  // The n-th strongest by a partial sort; then, in their order, every keypoint at least as strong
  // (the order is total: exactly n are).
  thread_local std::vector<std::uint64_t> key_buffer, ranked_buffer;
  std::vector<std::uint64_t>& keys = key_buffer;
  if (packedStrengthKeys(keypoints, keys)) {
    std::vector<std::uint64_t>& ranked = ranked_buffer;
    ranked.assign(keys.begin(), keys.end());
    std::nth_element(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(n - 1), ranked.end());
    const std::uint64_t weakest = ranked[n - 1];
    size_t kept = 0;
    for (size_t i = 0; i < keypoints.size(); ++i) {
      if (keys[i] <= weakest) {
        keypoints[kept++] = keypoints[i];
      }
    }
    keypoints.resize(kept);
    return;
  }
  std::vector<cv::KeyPoint> ranked = keypoints;
  std::nth_element(ranked.begin(), ranked.begin() + static_cast<std::ptrdiff_t>(n - 1), ranked.end(), stronger);
  const cv::KeyPoint weakest = ranked[n - 1];
  keypoints.erase(std::remove_if(keypoints.begin(), keypoints.end(),
                                 [&weakest](const cv::KeyPoint& kp) { return stronger(weakest, kp); }),
                  keypoints.end());
}

namespace {

// selectSpread of `keypoints` (more than n > 0 of them) into `selected`.
void selectSpreadInto(const std::vector<cv::KeyPoint>& keypoints, int n, cv::Size size,
                      std::vector<cv::KeyPoint>& selected) {
  const int cell = std::max(1, cvRound(std::sqrt(static_cast<double>(size.area()) / n)));
  const int cols = (size.width + cell - 1) / cell;
  const int rows = (size.height + cell - 1) / cell;
  auto bucketOf = [&](const cv::KeyPoint& kp) {
    const int bx = std::clamp(static_cast<int>(kp.pt.x) / cell, 0, cols - 1);
    const int by = std::clamp(static_cast<int>(kp.pt.y) / cell, 0, rows - 1);
    return by * cols + bx;
  };
  // All keypoints in one order, bucket after bucket, each bucket strongest first: by packed keys
  // (bucket, strength) where the keypoints allow, else by comparison.
  thread_local std::vector<std::uint64_t> key_buffer;
  thread_local std::vector<int> order_buffer, bucket_buffer;
  std::vector<std::uint64_t>& keys = key_buffer;
  std::vector<int>& order = order_buffer;
  std::vector<int>& bucket_of = bucket_buffer;
  order.resize(keypoints.size());
  bucket_of.resize(keypoints.size());
  for (size_t i = 0; i < keypoints.size(); ++i) {
    bucket_of[i] = bucketOf(keypoints[i]);
  }
  if (keypoints.size() < (1u << 16) && cols * rows < (1 << 15) && packedStrengthKeys(keypoints, keys)) {
    // (bucket, 65535 - response, y, x) does not fit 64 bits: sort (bucket, 65535 - response,
    // index) and break the rare ties of equal strength by position afterwards.
    for (size_t i = 0; i < keypoints.size(); ++i) {
      keys[i] = (static_cast<std::uint64_t>(bucket_of[i]) << 48) | ((keys[i] >> 32) << 16) | i;
    }
    std::sort(keys.begin(), keys.end());
    for (size_t i = 0; i < keys.size(); ++i) {
      order[i] = static_cast<int>(keys[i] & 0xFFFF);
    }
    for (size_t i = 0; i < keys.size();) {
      size_t j = i + 1;
      while (j < keys.size() && (keys[j] >> 16) == (keys[i] >> 16)) {
        ++j;
      }
      if (j - i > 1) {
        std::sort(order.begin() + static_cast<std::ptrdiff_t>(i), order.begin() + static_cast<std::ptrdiff_t>(j),
                  [&](int a, int b) { return stronger(keypoints[a], keypoints[b]); });
      }
      i = j;
    }
  } else {
    for (size_t i = 0; i < keypoints.size(); ++i) {
      order[i] = static_cast<int>(i);
    }
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return bucket_of[a] != bucket_of[b] ? bucket_of[a] < bucket_of[b] : stronger(keypoints[a], keypoints[b]);
    });
  }
  thread_local std::vector<int> begin_buffer, end_buffer;
  std::vector<int>& begin = begin_buffer;
  std::vector<int>& end = end_buffer;
  begin.clear();
  end.clear();
  for (size_t i = 0; i < order.size(); ++i) {
    if (i == 0 || bucket_of[order[i]] != bucket_of[order[i - 1]]) {
      begin.push_back(static_cast<int>(i));
      end.push_back(static_cast<int>(i));
    }
    ++end.back();
  }
  // Round r takes the r-th best of every cell; the last, partial round keeps its best responses.
  selected.clear();
  thread_local std::vector<cv::KeyPoint> round_buffer;
  std::vector<cv::KeyPoint>& round = round_buffer;
  for (int rank = 0; static_cast<int>(selected.size()) < n; ++rank) {
    round.clear();
    for (size_t b = 0; b < begin.size(); ++b) {
      if (begin[b] + rank < end[b]) {
        round.push_back(keypoints[order[begin[b] + rank]]);
      }
    }
    const size_t room = n - selected.size();
    if (round.size() > room) {
      std::partial_sort(round.begin(), round.begin() + static_cast<std::ptrdiff_t>(room), round.end(), stronger);
      round.resize(room);
    }
    selected.insert(selected.end(), round.begin(), round.end());
  }
}

}  // namespace

std::vector<cv::KeyPoint> selectSpread(std::vector<cv::KeyPoint> keypoints, int n, cv::Size size) {
  if (n <= 0) {
    return {};
  }
  if (static_cast<int>(keypoints.size()) <= n) {
    return keypoints;
  }
  std::vector<cv::KeyPoint> selected;
  selectSpreadInto(keypoints, n, size, selected);
  return selected;
}

namespace {

// The moments' weights over the patch's square: u (for m10) and v (for m01) inside the disc, 0
// outside, so that each row is one fixed-length loop the compiler vectorises.
struct MomentWeights {
  static constexpr int kSide = 2 * kOrientationRadius + 1;
  static constexpr int kRow = kSide + 1;  // one zero weight more: whole vectors
  std::array<std::array<std::int16_t, kRow>, kSide> u{}, v{};

  MomentWeights() {
    const std::array<int, kOrientationRadius + 1> u_max = patchHalfWidths();
    for (int dv = -kOrientationRadius; dv <= kOrientationRadius; ++dv) {
      for (int du = -u_max[std::abs(dv)]; du <= u_max[std::abs(dv)]; ++du) {
        u[dv + kOrientationRadius][du + kOrientationRadius] = static_cast<std::int16_t>(du);
        v[dv + kOrientationRadius][du + kOrientationRadius] = static_cast<std::int16_t>(dv);
      }
    }
  }
};

}  // namespace

void computeOrientation(const cv::Mat& level, std::vector<cv::KeyPoint>& keypoints) {
  static const MomentWeights weights;
  constexpr int r = kOrientationRadius;
  const cv::Rect inside(r, r, level.cols - 2 * r, level.rows - 2 * r);
  const std::ptrdiff_t step = static_cast<std::ptrdiff_t>(level.step);
  for (cv::KeyPoint& kp : keypoints) {
    const cv::Point c(cvRound(kp.pt.x), cvRound(kp.pt.y));
    if (!inside.contains(c)) {
      kp.angle = 0.0f;
      continue;
    }
    // Eq 4: moments m_pq = sum x^p y^q I(x, y) over the patch, centred on the keypoint.
    const std::uint8_t* corner = level.ptr<std::uint8_t>(c.y - r) + (c.x - r);
    std::int32_t m10 = 0;
    std::int32_t m01 = 0;
    for (int row = 0; row < MomentWeights::kSide; ++row) {
      const std::uint8_t* pixels = corner + row * step;
      const std::int16_t* wu = weights.u[row].data();
      const std::int16_t* wv = weights.v[row].data();
      for (int i = 0; i < MomentWeights::kRow; ++i) {
        const std::int16_t pixel = pixels[i];
        m10 += wu[i] * pixel;  // 16-bit products summed in 32 bits: a multiply-add per pair
        m01 += wv[i] * pixel;
      }
    }
    kp.angle = cv::fastAtan2(static_cast<float>(m01), static_cast<float>(m10));  // eqs 5-6
  }
}

// Everything one extraction works in, kept from call to call.
struct OrbExtractor::Workspace {
  struct Level {
    cv::Mat image;        // levels 1.. (level 0 is the extraction's image)
    LinearResize resize;  // from the level above
    ThresholdWorkspace threshold;
    CornerWorkspace corners;
    std::vector<cv::KeyPoint> keypoints;
    SmoothingBuffers smoothing;
    cv::Mat smoothed;
    StageTimings timings;
  };
  std::vector<Level> levels;
  std::vector<cv::Mat> pyramid;
  std::vector<cv::Size> sizes;
  std::vector<int> budgets, first;
  std::vector<cv::KeyPoint> selected;
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

Extraction OrbExtractor::extract(const cv::Mat& gray) const {
  Extraction out;
  extract(gray, out);
  return out;
}

void OrbExtractor::extract(const cv::Mat& gray, Extraction& out) const {
  if (!gray.empty() && gray.type() != CV_8UC1) {
    throw std::invalid_argument("extract: expected CV_8UC1, got " + cv::typeToString(gray.type()));
  }
  Stopwatch clock;
  out.timings = StageTimings();
  out.keypoints.clear();
  out.lambda = 0.0;
  out.poor_quality = false;
  out.inverted = false;
  out.noise = 0.0;
  if (params_.enhance_enabled) {
    ownOrRelease(out.image);
    EnhanceResult enhanced = enhance(gray, params_.enhance, out.image, params_.orb.threads);
    out.image = enhanced.image;
    out.lambda = enhanced.lambda;
    out.poor_quality = enhanced.poor_quality;
    out.inverted = enhanced.inverted;
  } else {
    out.image = gray;
  }
  out.timings.enhance_ms = clock.lap();
  Stopwatch wall;

  std::unique_ptr<Workspace> ws = acquire();
  struct ReturnToPool {
    const OrbExtractor* self;
    std::unique_ptr<Workspace>& ws;
    ~ReturnToPool() {
      ws->pyramid.clear();  // level 0 may be the caller's image: not kept alive by the pool
      self->release(std::move(ws));
    }
  } return_to_pool{this, ws};

  const OrbParams& orb = params_.orb;
  // An empty image has one empty level: its thresholds are the grid's (c_min, or the fixed
  // threshold), its corners none.
  std::vector<cv::Size>& sizes = ws->sizes;
  pyramidSizes(out.image.size(), orb.n_levels, orb.scale_factor, sizes);
  const int n_levels = static_cast<int>(sizes.size());
  ws->levels.resize(std::max(ws->levels.size(), sizes.size()));
  ws->pyramid.resize(sizes.size());
  if (n_levels > 0) {
    ws->pyramid[0] = out.image;
  }
  // Level l is level l - 1 resized: whichever thread first needs a level builds it and the ones
  // before it, in order, while others work on the levels that are there.
  std::mutex pyramid_mutex;
  std::atomic<int> built{1};
  auto ensureLevel = [&](int level, double& ms) {
    if (built.load(std::memory_order_acquire) > level) {
      return;
    }
    Stopwatch pyramid_clock;
    std::lock_guard<std::mutex> lock(pyramid_mutex);
    for (int next = built.load(std::memory_order_relaxed); next <= level; ++next) {
      cv::Mat& image = ws->levels[next].image;
      ws->levels[next].resize(ws->pyramid[next - 1], image, sizes[next], activeSimdLevel());
      ws->pyramid[next] = image;
      built.store(next + 1, std::memory_order_release);
    }
    ms += pyramid_clock.lap();
  };

  // Per level: the thresholds, the corners, and cv::ORB's smoothing for the descriptors.
  out.cell_thresholds.release();  // level 0's thresholds again below
  out.level_thresholds.resize(sizes.size());
  for (cv::Mat& t : out.level_thresholds) {
    ownOrRelease(t);
  }
  forEachLevel(n_levels, orb.threads, [&](int level) {
    Workspace::Level& l = ws->levels[level];
    l.timings = StageTimings();
    ensureLevel(level, l.timings.pyramid_ms);
    const cv::Mat& image = ws->pyramid[level];
    Stopwatch level_clock;
    cv::Mat& thresholds = out.level_thresholds[level];
    if (orb.threshold_mode == ThresholdMode::kAdaptive) {
      cellThresholds(image, params_.threshold, l.threshold, thresholds);
    } else {
      thresholds.create(params_.threshold.grid_size, params_.threshold.grid_size, CV_32S);
      thresholds.setTo(cv::Scalar(orb.fast_threshold));
    }
    l.timings.threshold_ms = level_clock.lap();
    detectCorners(image, thresholds, l.corners, l.keypoints);
    l.timings.fast_ms = level_clock.lap();
    if (!l.keypoints.empty()) {
      smoothForDescription(image, l.smoothing, l.smoothed);
    }
    l.timings.descriptor_ms = level_clock.lap();
  });
  out.cell_thresholds = n_levels > 0 ? out.level_thresholds.front() : cv::Mat();
  for (int level = 0; level < n_levels; ++level) {
    out.timings.pyramid_ms += ws->levels[level].timings.pyramid_ms;
    out.timings.threshold_ms += ws->levels[level].timings.threshold_ms;
    out.timings.fast_ms += ws->levels[level].timings.fast_ms;
  }
  clock.lap();

  // The frame's noise, where the candidates are chosen by it.
  out.noise = orb.max_features > 0 && orb.noise_floor > 0.0 ? estimateNoise(out.image) : 0.0;
  const double floor = orb.noise_floor * out.noise;
  if (orb.max_features > 0) {
    // Budget per level; what a level cannot use passes on to the next one.
    std::vector<int>& budgets = ws->budgets;
    levelBudgets(orb.max_features, orb.n_levels, orb.scale_factor, budgets);
    int carry = 0;
    for (int level = 0; level < n_levels; ++level) {
      std::vector<cv::KeyPoint>& kps = ws->levels[level].keypoints;
      const int budget = budgets[level] + carry;
      if (orb.noise_floor > 0.0) {
        // The corners that stand noise_floor x the noise above it, and at least the budget's
        // strongest: in a clean frame every real corner, in a noisy one the strongest only.
        const auto above =
            std::count_if(kps.begin(), kps.end(), [floor](const cv::KeyPoint& kp) { return kp.response >= floor; });
        keepStrongest(kps, static_cast<size_t>(std::max<std::ptrdiff_t>(above, budget)));
      } else if (orb.candidate_ratio > 0.0) {
        keepStrongest(kps, static_cast<size_t>(std::ceil(orb.candidate_ratio * budget)));
      }
      if (budget <= 0) {
        kps.clear();
      } else if (static_cast<int>(kps.size()) > budget) {
        selectSpreadInto(kps, budget, sizes[level], ws->selected);
        kps.swap(ws->selected);
      }
      carry = budget - static_cast<int>(kps.size());
    }
  }
  out.timings.select_ms = clock.lap();

  // Orientation and descriptors, each level into its own rows.
  std::vector<int>& first = ws->first;
  first.assign(n_levels + 1, 0);
  for (int level = 0; level < n_levels; ++level) {
    first[level + 1] = first[level] + static_cast<int>(ws->levels[level].keypoints.size());
  }
  ownOrRelease(out.descriptors);
  out.descriptors.create(first[n_levels], kDescriptorBytes, CV_8U);
  out.keypoints.resize(static_cast<size_t>(first[n_levels]));
  forEachLevel(n_levels, orb.threads, [&](int level) {
    Workspace::Level& l = ws->levels[level];
    if (l.keypoints.empty()) {
      return;
    }
    Stopwatch level_clock;
    computeOrientation(ws->pyramid[level], l.keypoints);
    l.timings.orientation_ms = level_clock.lap();
    describe(l.smoothed, l.keypoints, out.descriptors, first[level]);
    const float scale = levelScale(orb.scale_factor, level);
    for (size_t i = 0; i < l.keypoints.size(); ++i) {
      cv::KeyPoint kp = l.keypoints[i];
      kp.pt *= scale;
      kp.size = kPatchSize * scale;
      kp.octave = level;
      out.keypoints[first[level] + i] = kp;
    }
    l.timings.descriptor_ms += level_clock.lap();
  });
  for (int level = 0; level < n_levels; ++level) {
    out.timings.orientation_ms += ws->levels[level].timings.orientation_ms;
    out.timings.descriptor_ms += ws->levels[level].timings.descriptor_ms;
  }
  out.timings.extract_ms = wall.lap();
}

}  // namespace enhanced_orb
