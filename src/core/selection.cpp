#include "enhanced_orb/selection.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace enhanced_orb {
namespace {

// Stronger response first; position breaks ties, so that every selection is deterministic.
bool stronger(const cv::KeyPoint& a, const cv::KeyPoint& b) {
  if (a.response != b.response) {
    return a.response > b.response;
  }
  return a.pt.y != b.pt.y ? a.pt.y < b.pt.y : a.pt.x < b.pt.x;
}

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

// The keys of keypoints whose responses are integers in [0, 65535] at integer positions in
// [0, 65535] (the extractor's corners): (65535 - response) << 32 | y << 16 | x, so that ascending
// keys are `stronger` order. False, with `keys` unspecified, for any other keypoint.
bool packedStrengthKeys(const std::vector<cv::KeyPoint>& keypoints, std::vector<std::uint64_t>& keys) {
  // v as an integer in [0, 65535], or -1 when it is not one (NaN fails the range test). Converting
  // and back is the whole-number test: a conversion truncates, exactly for these values.
  auto whole = [](float v) {
    if (!(v >= 0.0f && v <= 65535.0f)) {
      return -1;
    }
    const int i = static_cast<int>(v);
    return static_cast<float>(i) == v ? i : -1;
  };
  keys.resize(keypoints.size());
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const cv::KeyPoint& kp = keypoints[i];
    const int r = whole(kp.response), x = whole(kp.pt.x), y = whole(kp.pt.y);
    if ((r | x | y) < 0) {
      return false;
    }
    keys[i] = (static_cast<std::uint64_t>(65535 - r) << 32) | (static_cast<std::uint64_t>(y) << 16) |
              static_cast<std::uint64_t>(x);
  }
  return true;
}

// keepStrongest() with the workspace's buffers.
void keepStrongest(std::vector<cv::KeyPoint>& keypoints, size_t n, std::vector<std::uint64_t>& keys,
                   std::vector<std::uint64_t>& ranked) {
  if (keypoints.size() <= n) {
    return;
  }
  if (n == 0) {
    keypoints.clear();
    return;
  }
  // The n-th strongest by a partial sort; then, in their order, every keypoint at least as strong
  // (the order is total: exactly n are).
  if (packedStrengthKeys(keypoints, keys)) {
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
  std::vector<cv::KeyPoint> by_strength = keypoints;
  std::nth_element(by_strength.begin(), by_strength.begin() + static_cast<std::ptrdiff_t>(n - 1), by_strength.end(),
                   stronger);
  const cv::KeyPoint weakest = by_strength[n - 1];
  keypoints.erase(std::remove_if(keypoints.begin(), keypoints.end(),
                                 [&weakest](const cv::KeyPoint& kp) { return stronger(weakest, kp); }),
                  keypoints.end());
}

// Every keypoint's index in one order, bucket after bucket (square cells of `cell` pixels,
// `cols` a row), each bucket strongest first: by packed keys (bucket, strength) where the
// keypoints allow, else by comparison. ws.order gets the order, ws.bucket_of each keypoint's bucket.
void bucketOrder(const std::vector<cv::KeyPoint>& keypoints, int cell, int cols, int rows, SelectionWorkspace& ws) {
  std::vector<int>& order = ws.order;
  std::vector<int>& bucket_of = ws.bucket_of;
  std::vector<std::uint64_t>& keys = ws.keys;
  order.resize(keypoints.size());
  bucket_of.resize(keypoints.size());
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const int bx = std::clamp(static_cast<int>(keypoints[i].pt.x) / cell, 0, cols - 1);
    const int by = std::clamp(static_cast<int>(keypoints[i].pt.y) / cell, 0, rows - 1);
    bucket_of[i] = by * cols + bx;
  }
  if (keypoints.size() < (1u << 16) && packedStrengthKeys(keypoints, keys)) {
    // Counted into their buckets (in index order), then each bucket sorted by (65535 - response,
    // index): the keys of one bucket are few, so this is cheaper than one sort of all of them by
    // (bucket, strength, index), whose order it gives. The rare ties of equal strength are broken by
    // position afterwards.
    const int buckets = cols * rows;
    std::vector<int>& start = ws.bucket_start;
    start.assign(static_cast<size_t>(buckets) + 1, 0);
    for (size_t i = 0; i < keypoints.size(); ++i) {
      ++start[bucket_of[i] + 1];
    }
    for (int b = 0; b < buckets; ++b) {
      start[b + 1] += start[b];
    }
    std::vector<int>& next = ws.bucket_next;
    next.assign(start.begin(), start.end() - 1);
    std::vector<std::uint64_t>& ranked = ws.ranked;
    ranked.resize(keypoints.size());
    for (size_t i = 0; i < keypoints.size(); ++i) {
      ranked[next[bucket_of[i]]++] = ((keys[i] >> 32) << 16) | i;
    }
    for (int b = 0; b < buckets; ++b) {
      std::sort(ranked.begin() + start[b], ranked.begin() + start[b + 1]);
    }
    for (size_t i = 0; i < ranked.size(); ++i) {
      order[i] = static_cast<int>(ranked[i] & 0xFFFF);
    }
    for (size_t i = 0; i < ranked.size();) {
      size_t j = i + 1;
      while (j < ranked.size() && (ranked[j] >> 16) == (ranked[i] >> 16) &&
             bucket_of[order[j]] == bucket_of[order[i]]) {
        ++j;
      }
      if (j - i > 1) {
        std::sort(order.begin() + static_cast<std::ptrdiff_t>(i), order.begin() + static_cast<std::ptrdiff_t>(j),
                  [&](int a, int b) { return stronger(keypoints[a], keypoints[b]); });
      }
      i = j;
    }
    return;
  }
  for (size_t i = 0; i < keypoints.size(); ++i) {
    order[i] = static_cast<int>(i);
  }
  std::sort(order.begin(), order.end(), [&](int a, int b) {
    return bucket_of[a] != bucket_of[b] ? bucket_of[a] < bucket_of[b] : stronger(keypoints[a], keypoints[b]);
  });
}

// selectSpread of `keypoints` (more than n > 0 of them) into ws.selected.
void selectSpreadInto(const std::vector<cv::KeyPoint>& keypoints, int n, cv::Size size, SelectionWorkspace& ws) {
  const int cell = std::max(1, cvRound(std::sqrt(static_cast<double>(size.area()) / n)));
  const int cols = (size.width + cell - 1) / cell;
  const int rows = (size.height + cell - 1) / cell;
  bucketOrder(keypoints, cell, cols, rows, ws);
  // Each bucket's run [begin, end) in the order.
  ws.begin.clear();
  ws.end.clear();
  for (size_t i = 0; i < ws.order.size(); ++i) {
    if (i == 0 || ws.bucket_of[ws.order[i]] != ws.bucket_of[ws.order[i - 1]]) {
      ws.begin.push_back(static_cast<int>(i));
      ws.end.push_back(static_cast<int>(i));
    }
    ++ws.end.back();
  }
  // Round r takes the r-th best of every cell; the last, partial round keeps its best responses.
  ws.selected.clear();
  for (int rank = 0; static_cast<int>(ws.selected.size()) < n; ++rank) {
    ws.round.clear();
    for (size_t b = 0; b < ws.begin.size(); ++b) {
      if (ws.begin[b] + rank < ws.end[b]) {
        ws.round.push_back(keypoints[ws.order[ws.begin[b] + rank]]);
      }
    }
    const size_t room = n - ws.selected.size();
    if (ws.round.size() > room) {
      std::partial_sort(ws.round.begin(), ws.round.begin() + static_cast<std::ptrdiff_t>(room), ws.round.end(),
                        stronger);
      ws.round.resize(room);
    }
    ws.selected.insert(ws.selected.end(), ws.round.begin(), ws.round.end());
  }
}

}  // namespace

std::vector<int> levelBudgets(int total, int n_levels, double scale_factor) {
  std::vector<int> budgets;
  levelBudgets(total, n_levels, scale_factor, budgets);
  return budgets;
}

void keepStrongest(std::vector<cv::KeyPoint>& keypoints, size_t n) {
  std::vector<std::uint64_t> keys, ranked;
  keepStrongest(keypoints, n, keys, ranked);
}

std::vector<cv::KeyPoint> selectSpread(std::vector<cv::KeyPoint> keypoints, int n, cv::Size size) {
  if (n <= 0) {
    return {};
  }
  if (static_cast<int>(keypoints.size()) <= n) {
    return keypoints;
  }
  SelectionWorkspace ws;
  selectSpreadInto(keypoints, n, size, ws);
  return ws.selected;
}

void selectByBudget(const OrbParams& orb, double noise, const std::vector<cv::Size>& sizes,
                    std::vector<std::vector<cv::KeyPoint>>& levels, SelectionWorkspace& ws,
                    const std::function<void(size_t level)>& complete) {
  levelBudgets(orb.max_features, orb.n_levels, orb.scale_factor, ws.budgets);
  const double floor = orb.noise_floor * noise;
  int carry = 0;
  for (size_t level = 0; level < sizes.size(); ++level) {
    std::vector<cv::KeyPoint>& kps = levels[level];
    const int budget = ws.budgets[level] + carry;
    if (orb.noise_floor > 0.0) {
      if (complete && static_cast<int>(kps.size()) < budget) {
        complete(level);
      }
      // The corners that stand noise_floor x the noise above it, and at least the budget's
      // strongest: in a clean frame every real corner, in a noisy one the strongest only; with
      // floor_candidate_ratio, at most that many times the budget of them.
      std::ptrdiff_t above =
          std::count_if(kps.begin(), kps.end(), [floor](const cv::KeyPoint& kp) { return kp.response >= floor; });
      if (orb.floor_candidate_ratio > 0.0) {
        above = std::min(above, static_cast<std::ptrdiff_t>(std::ceil(orb.floor_candidate_ratio * budget)));
      }
      keepStrongest(kps, static_cast<size_t>(std::max<std::ptrdiff_t>(above, budget)), ws.keys, ws.ranked);
    } else if (orb.candidate_ratio > 0.0) {
      keepStrongest(kps, static_cast<size_t>(std::ceil(orb.candidate_ratio * budget)), ws.keys, ws.ranked);
    }
    if (budget <= 0) {
      kps.clear();
    } else if (static_cast<int>(kps.size()) > budget) {
      selectSpreadInto(kps, budget, sizes[level], ws);
      kps.swap(ws.selected);
    }
    carry = budget - static_cast<int>(kps.size());
  }
}

}  // namespace enhanced_orb
