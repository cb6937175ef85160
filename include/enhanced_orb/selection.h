// Which corners a budget keeps: each level's share, the candidates, the spread over the image.
#ifndef ENHANCED_ORB_SELECTION_H
#define ENHANCED_ORB_SELECTION_H

#include <cstdint>
#include <functional>
#include <vector>

#include <opencv2/core.hpp>

#include "enhanced_orb/params.h"

namespace enhanced_orb {

// How a budget of `total` keypoints splits over the levels: geometric with ratio 1/scale_factor
// (as ORB-SLAM); the last level takes the rounding remainder.
std::vector<int> levelBudgets(int total, int n_levels, double scale_factor);

// Keeps the `n` strongest keypoints (by response; ties by position, y then x), in their order.
void keepStrongest(std::vector<cv::KeyPoint>& keypoints, size_t n);

// Keeps at most `n` keypoints, spread over the image: keypoints are bucketed in square cells of
// about sqrt(area / n) pixels, and taken best response first from every cell in turn: round r
// takes each cell's r-th best, cell by cell; the last, partial round its best responses, best
// first. Fewer than `n` keypoints are returned as they are.
std::vector<cv::KeyPoint> selectSpread(std::vector<cv::KeyPoint> keypoints, int n, cv::Size size);

// What selectByBudget() reuses from call to call.
struct SelectionWorkspace {
  std::vector<int> budgets;
  std::vector<std::uint64_t> keys, ranked;
  std::vector<int> order, bucket_of, begin, end, bucket_start, bucket_next;
  std::vector<cv::KeyPoint> round, selected;
};

// Cuts the corners of each level (levels[l] for the n_levels first) to the budget
// orb.max_features (> 0): each level gets its levelBudgets() share plus what the levels before it
// could not use; its candidates are its corners scoring at least orb.noise_floor x `noise` (and at
// least its share's strongest; at most its orb.floor_candidate_ratio x share strongest where that is
// > 0) when noise_floor > 0, else its candidate_ratio x share strongest
// (every corner when candidate_ratio is 0); the share is spread over them as selectSpread() does.
// `complete`, where given, is for levels whose corners were found at the noise floor only (every
// corner scoring at least noise_floor x `noise`): called with a level that has fewer of them than
// its share, it puts every corner of that level in levels[level], as the selection then needs them.
void selectByBudget(const OrbParams& orb, double noise, const std::vector<cv::Size>& sizes,
                    std::vector<std::vector<cv::KeyPoint>>& levels, SelectionWorkspace& ws,
                    const std::function<void(size_t level)>& complete = nullptr);

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_SELECTION_H
