#include "enhanced_orb/evaluation/orb_slam_style.h"

#include <algorithm>
#include <cmath>
#include <list>

#include <opencv2/features2d.hpp>

#include "enhanced_orb/orb_extractor.h"

namespace enhanced_orb {
namespace evaluation {
namespace {

struct Node {
  cv::Rect2f area;
  std::vector<cv::KeyPoint> keypoints;
  bool leaf() const { return keypoints.size() <= 1; }
};

// The four children of a node (empty ones dropped).
std::vector<Node> split(const Node& node) {
  const float hw = node.area.width / 2, hh = node.area.height / 2;
  std::vector<Node> children(4);
  for (int i = 0; i < 4; ++i) {
    children[i].area = cv::Rect2f(node.area.x + (i % 2) * hw, node.area.y + (i / 2) * hh, hw, hh);
  }
  for (const cv::KeyPoint& kp : node.keypoints) {
    const int i = (kp.pt.x >= node.area.x + hw ? 1 : 0) + (kp.pt.y >= node.area.y + hh ? 2 : 0);
    children[i].keypoints.push_back(kp);
  }
  children.erase(std::remove_if(children.begin(), children.end(), [](const Node& c) { return c.keypoints.empty(); }),
                 children.end());
  return children;
}

bool stronger(const cv::KeyPoint& a, const cv::KeyPoint& b) {
  return a.response > b.response;
}

}  // namespace

std::vector<cv::KeyPoint> distributeQuadtree(const std::vector<cv::KeyPoint>& keypoints, cv::Rect2f region, int n) {
  if (n <= 0 || keypoints.empty()) {
    return {};
  }
  const int n_initial = std::max(1, static_cast<int>(std::lround(region.width / std::max(1.0f, region.height))));
  const float width = region.width / n_initial;
  std::list<Node> nodes;
  std::vector<Node> initial(n_initial);
  for (int i = 0; i < n_initial; ++i) {
    initial[i].area = cv::Rect2f(region.x + i * width, region.y, width, region.height);
  }
  for (const cv::KeyPoint& kp : keypoints) {
    const int i = std::clamp(static_cast<int>((kp.pt.x - region.x) / width), 0, n_initial - 1);
    initial[i].keypoints.push_back(kp);
  }
  for (Node& node : initial) {
    if (!node.keypoints.empty()) {
      nodes.push_back(std::move(node));
    }
  }
  while (static_cast<int>(nodes.size()) < n) {
    std::vector<std::list<Node>::iterator> splittable;
    for (auto it = nodes.begin(); it != nodes.end(); ++it) {
      if (!it->leaf()) {
        splittable.push_back(it);
      }
    }
    if (splittable.empty()) {
      break;
    }
    // Splitting all of them could overshoot: then the fullest go first, until there are n.
    const bool last_round = static_cast<int>(nodes.size() + 3 * splittable.size()) > n;
    if (last_round) {
      std::stable_sort(splittable.begin(), splittable.end(),
                       [](auto a, auto b) { return a->keypoints.size() > b->keypoints.size(); });
    }
    for (auto it : splittable) {
      for (Node& child : split(*it)) {
        nodes.push_back(std::move(child));
      }
      nodes.erase(it);
      if (last_round && static_cast<int>(nodes.size()) >= n) {
        break;
      }
    }
  }
  std::vector<cv::KeyPoint> kept;
  for (const Node& node : nodes) {
    kept.push_back(*std::max_element(node.keypoints.begin(), node.keypoints.end(),
                                     [](const cv::KeyPoint& a, const cv::KeyPoint& b) { return stronger(b, a); }));
  }
  if (static_cast<int>(kept.size()) > n) {  // a split adds up to three nodes: the strongest n stay
    std::partial_sort(kept.begin(), kept.begin() + n, kept.end(), stronger);
    kept.resize(n);
  }
  return kept;
}

OrbSlamStyleExtractor::OrbSlamStyleExtractor(const OrbSlamStyleParams& params)
    : params_(params),
      describer_(cv::ORB::create(params.n_features, static_cast<float>(params.scale_factor), params.n_levels)) {}

void OrbSlamStyleExtractor::extract(const cv::Mat& gray, std::vector<cv::KeyPoint>& keypoints,
                                    cv::Mat& descriptors) const {
  keypoints.clear();
  descriptors.release();
  if (gray.empty()) {
    return;
  }
  const std::vector<cv::Mat> pyramid = buildPyramid(gray, params_.n_levels, params_.scale_factor);
  const std::vector<int> budgets = levelBudgets(params_.n_features, params_.n_levels, params_.scale_factor);
  constexpr int kBorder = kEdgeThreshold - 3;  // FAST reads 3 px around a corner
  for (size_t level = 0; level < pyramid.size(); ++level) {
    const cv::Mat& image = pyramid[level];
    const int width = image.cols - 2 * kBorder, height = image.rows - 2 * kBorder;
    if (width <= 0 || height <= 0) {
      continue;
    }
    const int cols = std::max(1, width / params_.cell), rows = std::max(1, height / params_.cell);
    const int cell_w = (width + cols - 1) / cols, cell_h = (height + rows - 1) / rows;
    std::vector<cv::KeyPoint> corners, found;
    for (int r = 0; r < rows; ++r) {
      for (int c = 0; c < cols; ++c) {
        // The cell widened by FAST's 3-pixel radius on each side.
        const int x0 = kBorder - 3 + c * cell_w, y0 = kBorder - 3 + r * cell_h;
        const int x1 = std::min(x0 + cell_w + 6, image.cols - kBorder + 3);
        const int y1 = std::min(y0 + cell_h + 6, image.rows - kBorder + 3);
        if (x1 - x0 < 7 || y1 - y0 < 7) {
          continue;
        }
        const cv::Mat window = image(cv::Rect(x0, y0, x1 - x0, y1 - y0));
        cv::FAST(window, found, params_.ini_fast, true);
        if (found.empty()) {
          cv::FAST(window, found, params_.min_fast, true);
        }
        for (cv::KeyPoint kp : found) {
          kp.pt += cv::Point2f(static_cast<float>(x0), static_cast<float>(y0));
          corners.push_back(kp);
        }
      }
    }
    std::vector<cv::KeyPoint> kept = distributeQuadtree(
        corners, cv::Rect2f(kBorder, kBorder, static_cast<float>(width), static_cast<float>(height)), budgets[level]);
    computeOrientation(image, kept);
    const float scale = static_cast<float>(std::pow(params_.scale_factor, static_cast<double>(level)));
    for (cv::KeyPoint& kp : kept) {
      kp.pt *= scale;
      kp.size = kPatchSize * scale;
      kp.octave = static_cast<int>(level);
      keypoints.push_back(kp);
    }
  }
  describer_->compute(gray, keypoints, descriptors);
}

}  // namespace evaluation
}  // namespace enhanced_orb
