#include "enhanced_orb/evaluation/metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include <opencv2/calib3d.hpp>
#include <opencv2/features2d.hpp>

namespace enhanced_orb {
namespace evaluation {

GroundTruth identity(double tolerance) {
  return [tolerance](const cv::Point2f& p1, const cv::Point2f& p2) { return cv::norm(p1 - p2) <= tolerance; };
}

std::vector<cv::DMatch> mutualMatches(const cv::Mat& d1, const cv::Mat& d2) {
  std::vector<cv::DMatch> matches;
  if (!d1.empty() && !d2.empty()) {
    cv::BFMatcher(cv::NORM_HAMMING, true).match(d1, d2, matches);
  }
  return matches;
}

MatchCounts matchAndCount(const std::vector<cv::KeyPoint>& kp1, const cv::Mat& d1, const std::vector<cv::KeyPoint>& kp2,
                          const cv::Mat& d2, const GroundTruth& truth) {
  MatchCounts counts;
  const std::vector<cv::DMatch> matches = mutualMatches(d1, d2);
  counts.matches = static_cast<int>(matches.size());
  for (const cv::DMatch& m : matches) {
    counts.correct += truth(kp1[m.queryIdx].pt, kp2[m.trainIdx].pt);
  }
  return counts;
}

double repeatability(const std::vector<cv::KeyPoint>& kp_a, const std::vector<cv::KeyPoint>& kp_b, double tolerance) {
  if (kp_a.empty() || kp_b.empty()) {
    return 0.0;
  }
  // Count from the smaller set, so that the share cannot exceed 1 where keypoints cluster.
  const bool a_smaller = kp_a.size() <= kp_b.size();
  const std::vector<cv::KeyPoint>& kp1 = a_smaller ? kp_a : kp_b;
  const std::vector<cv::KeyPoint>& kp2 = a_smaller ? kp_b : kp_a;
  // Buckets of `tolerance` pixels: a neighbour within tolerance lies in the 3 x 3 buckets around.
  auto key = [tolerance](float x, float y) {
    return (static_cast<std::int64_t>(std::floor(x / tolerance)) << 32) ^
           static_cast<std::uint32_t>(static_cast<std::int32_t>(std::floor(y / tolerance)));
  };
  std::unordered_map<std::int64_t, std::vector<cv::Point2f>> buckets;
  for (const cv::KeyPoint& kp : kp2) {
    buckets[key(kp.pt.x, kp.pt.y)].push_back(kp.pt);
  }
  int repeated = 0;
  for (const cv::KeyPoint& kp : kp1) {
    bool found = false;
    for (int dy = -1; dy <= 1 && !found; ++dy) {
      for (int dx = -1; dx <= 1 && !found; ++dx) {
        auto it = buckets.find(
            key(kp.pt.x + dx * static_cast<float>(tolerance), kp.pt.y + dy * static_cast<float>(tolerance)));
        if (it == buckets.end()) {
          continue;
        }
        for (const cv::Point2f& p : it->second) {
          if (cv::norm(p - kp.pt) <= tolerance) {
            found = true;
            break;
          }
        }
      }
    }
    repeated += found;
  }
  return static_cast<double>(repeated) / static_cast<double>(kp1.size());
}

std::optional<Camera> readCamera(const std::string& mav0, const std::string& camera) {
  try {
    // EuRoC ships its sensor.yaml files without the "%YAML:1.0" line cv::FileStorage needs to
    // read YAML: read the text and put the line in front when it is missing.
    std::ifstream in(mav0 + "/" + camera + "/sensor.yaml");
    if (!in) {
      return std::nullopt;
    }
    std::stringstream text;
    text << in.rdbuf();
    std::string yaml = text.str();
    if (yaml.rfind("%YAML", 0) != 0) {
      yaml = "%YAML:1.0\n" + yaml;
    }
    cv::FileStorage fs(yaml, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
    if (!fs.isOpened()) {
      return std::nullopt;
    }
    std::vector<double> intrinsics, distortion, t_bs;
    fs["intrinsics"] >> intrinsics;
    fs["distortion_coefficients"] >> distortion;
    fs["T_BS"]["data"] >> t_bs;
    if (intrinsics.size() != 4 || distortion.size() != 4 || t_bs.size() != 16) {
      return std::nullopt;
    }
    Camera cam;
    cam.K = cv::Matx33d(intrinsics[0], 0, intrinsics[2], 0, intrinsics[1], intrinsics[3], 0, 0, 1);
    cam.distortion = distortion;
    cam.T_BS = cv::Matx44d(t_bs.data());
    return cam;
  } catch (const cv::Exception&) {
    return std::nullopt;
  }
}

std::optional<Trajectory> Trajectory::read(const std::string& mav0) {
  std::ifstream in(mav0 + "/state_groundtruth_estimate0/data.csv");
  if (!in) {
    return std::nullopt;
  }
  Trajectory t;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') {
      continue;
    }
    std::vector<double> v;
    std::istringstream fields(line);
    std::string field;
    std::int64_t stamp = 0;
    for (int i = 0; std::getline(fields, field, ','); ++i) {
      if (i == 0) {
        stamp = std::stoll(field);
      } else {
        v.push_back(std::stod(field));
      }
    }
    if (v.size() < 7) {
      continue;
    }
    // p_RS_R (x, y, z), q_RS (w, x, y, z): the body in the world.
    const cv::Vec4d q = cv::normalize(cv::Vec4d(v[3], v[4], v[5], v[6]));
    const double w = q[0], x = q[1], y = q[2], z = q[3];
    t.poses_[stamp] = cv::Matx44d(1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w), v[0],
                                  2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w), v[1],
                                  2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y), v[2], 0, 0, 0, 1);
  }
  if (t.poses_.empty()) {
    return std::nullopt;
  }
  return t;
}

std::optional<cv::Matx44d> Trajectory::at(std::int64_t stamp, std::int64_t tolerance_ns) const {
  auto after = poses_.lower_bound(stamp);
  std::optional<std::pair<std::int64_t, cv::Matx44d>> best;
  for (auto it : {after, after == poses_.begin() ? poses_.end() : std::prev(after)}) {
    if (it != poses_.end() && (!best || std::llabs(it->first - stamp) < std::llabs(best->first - stamp))) {
      best = *it;
    }
  }
  if (!best || std::llabs(best->first - stamp) > tolerance_ns) {
    return std::nullopt;
  }
  return best->second;
}

std::optional<cv::Matx44d> Trajectory::interpolated(std::int64_t stamp, std::int64_t tolerance_ns) const {
  const auto after = poses_.lower_bound(stamp);
  if (after != poses_.end() && after->first == stamp) {
    return after->second;
  }
  if (after == poses_.end() || after == poses_.begin()) {
    return std::nullopt;
  }
  const auto before = std::prev(after);
  if (stamp - before->first > tolerance_ns || after->first - stamp > tolerance_ns) {
    return std::nullopt;
  }
  const double s = static_cast<double>(stamp - before->first) / static_cast<double>(after->first - before->first);
  const cv::Matx33d R0 = before->second.get_minor<3, 3>(0, 0);
  const cv::Matx33d R1 = after->second.get_minor<3, 3>(0, 0);
  cv::Vec3d w;
  cv::Rodrigues(R0.t() * R1, w);
  cv::Matx33d dR;
  cv::Rodrigues(cv::Vec3d(w * s), dR);
  const cv::Matx33d R = R0 * dR;
  cv::Matx44d T = cv::Matx44d::eye();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      T(r, c) = R(r, c);
    }
    T(r, 3) = (1.0 - s) * before->second(r, 3) + s * after->second(r, 3);
  }
  return T;
}

RelativePose groundTruthPose(const Camera& camera1, const cv::Matx44d& T_WB1, const Camera& camera2,
                             const cv::Matx44d& T_WB2) {
  // Camera 1 in camera 2: T_C2C1 = (T_WB2 T_BS2)^-1 T_WB1 T_BS1.
  const cv::Matx44d T_21 = (T_WB2 * camera2.T_BS).inv() * (T_WB1 * camera1.T_BS);
  return {T_21.get_minor<3, 3>(0, 0), cv::Vec3d(T_21(0, 3), T_21(1, 3), T_21(2, 3))};
}

bool isStatic(const RelativePose& pose, double min_baseline) {
  return cv::norm(pose.t) < min_baseline;
}

GroundTruth rotationOnly(const Camera& camera1, const Camera& camera2, const RelativePose& pose, double tolerance) {
  const cv::Matx33d H = camera2.K * pose.R * camera1.K.inv();
  return [H, camera1, camera2, tolerance](const cv::Point2f& p1, const cv::Point2f& p2) {
    std::vector<cv::Point2f> u1, u2;
    cv::undistortPoints(std::vector<cv::Point2f>{p1}, u1, camera1.K, camera1.distortion, cv::noArray(), camera1.K);
    cv::undistortPoints(std::vector<cv::Point2f>{p2}, u2, camera2.K, camera2.distortion, cv::noArray(), camera2.K);
    const cv::Vec3d x = H * cv::Vec3d(u1[0].x, u1[0].y, 1.0);
    return std::hypot(x[0] / x[2] - u2[0].x, x[1] / x[2] - u2[0].y) <= tolerance;
  };
}

PoseEstimate estimatePose(const Camera& camera1, const Camera& camera2, const std::vector<cv::Point2f>& p1,
                          const std::vector<cv::Point2f>& p2, int draw) {
  PoseEstimate estimate;
  if (p1.size() < 5 || p1.size() != p2.size()) {
    return estimate;
  }
  std::vector<cv::Point2f> n1, n2;
  cv::undistortPoints(p1, n1, camera1.K, camera1.distortion);
  cv::undistortPoints(p2, n2, camera2.K, camera2.distortion);
  if (draw > 0) {
    // findEssentialMat's RANSAC seeds its own generator: shuffled matches give other samples.
    cv::RNG rng(static_cast<std::uint64_t>(draw));
    for (int i = static_cast<int>(n1.size()) - 1; i > 0; --i) {
      const int j = rng.uniform(0, i + 1);
      std::swap(n1[i], n1[j]);
      std::swap(n2[i], n2[j]);
    }
  }
  const double focal = 0.25 * (camera1.K(0, 0) + camera1.K(1, 1) + camera2.K(0, 0) + camera2.K(1, 1));
  cv::Mat mask;
  const cv::Mat E = cv::findEssentialMat(n1, n2, cv::Mat::eye(3, 3, CV_64F), cv::RANSAC, 0.999, 1.0 / focal, mask);
  if (E.rows != 3 || E.cols != 3) {
    return estimate;  // none, or several solutions stacked: treat as a failure
  }
  cv::Mat R, t;
  estimate.inliers = cv::recoverPose(E, n1, n2, cv::Mat::eye(3, 3, CV_64F), R, t, mask);
  estimate.ok = estimate.inliers >= 5;
  estimate.R = cv::Matx33d(R);
  estimate.t = cv::Vec3d(t);
  return estimate;
}

PoseError poseError(const PoseEstimate& estimate, const RelativePose& truth) {
  PoseError error;
  if (!estimate.ok) {
    return error;
  }
  const cv::Matx33d dR = estimate.R.t() * truth.R;
  const double cos_r = std::clamp((cv::trace(dR) - 1.0) / 2.0, -1.0, 1.0);
  error.rotation_deg = std::acos(cos_r) * 180.0 / CV_PI;
  const double norms = cv::norm(estimate.t) * cv::norm(truth.t);
  if (norms > 0.0) {
    const double cos_t = std::clamp(std::abs(estimate.t.dot(truth.t)) / norms, 0.0, 1.0);
    error.translation_deg = std::acos(cos_t) * 180.0 / CV_PI;
  }
  return error;
}

DrawnPose medianPoseOfDraws(const Camera& camera1, const Camera& camera2, const std::vector<cv::Point2f>& p1,
                            const std::vector<cv::Point2f>& p2, const RelativePose& truth, int draws) {
  std::vector<DrawnPose> drawn;
  for (int draw = 0; draw < std::max(1, draws); ++draw) {
    const PoseEstimate estimate = estimatePose(camera1, camera2, p1, p2, draw);
    drawn.push_back({estimate, poseError(estimate, truth)});
  }
  const auto middle = drawn.begin() + static_cast<std::ptrdiff_t>((drawn.size() - 1) / 2);
  std::nth_element(drawn.begin(), middle, drawn.end(),
                   [](const DrawnPose& a, const DrawnPose& b) { return a.error.max() < b.error.max(); });
  return *middle;
}

double poseAuc(std::vector<double> errors, double threshold) {
  if (errors.empty() || threshold <= 0.0) {
    return 0.0;
  }
  std::sort(errors.begin(), errors.end());
  // Recall r(e) = share of errors <= e, a step function: integrate it over [0, threshold].
  const double n = static_cast<double>(errors.size());
  double area = 0.0;
  double previous = 0.0;
  for (size_t i = 0; i < errors.size() && errors[i] < threshold; ++i) {
    area += (errors[i] - previous) * (static_cast<double>(i) / n);
    previous = errors[i];
  }
  const double reached =
      static_cast<double>(std::upper_bound(errors.begin(), errors.end(), threshold - 1e-12) - errors.begin());
  area += (threshold - previous) * (reached / n);
  return area / threshold;
}

GroundTruth epipolar(const Camera& camera, const cv::Matx44d& T_WB1, const cv::Matx44d& T_WB2, double tolerance) {
  return epipolar(camera, T_WB1, camera, T_WB2, tolerance);
}

GroundTruth epipolar(const Camera& camera1, const cv::Matx44d& T_WB1, const Camera& camera2, const cv::Matx44d& T_WB2,
                     double tolerance) {
  // E = [t]x R maps normalised x1 to a line of x2.
  const RelativePose pose = groundTruthPose(camera1, T_WB1, camera2, T_WB2);
  const cv::Matx33d R = pose.R;
  const cv::Vec3d t = pose.t;
  const cv::Matx33d tx(0, -t[2], t[1], t[2], 0, -t[0], -t[1], t[0], 0);
  const cv::Matx33d E = tx * R;
  const double focal = 0.25 * (camera1.K(0, 0) + camera1.K(1, 1) + camera2.K(0, 0) + camera2.K(1, 1));
  return [E, focal, camera1, camera2, tolerance](const cv::Point2f& p1, const cv::Point2f& p2) {
    std::vector<cv::Point2f> n1, n2;
    cv::undistortPoints(std::vector<cv::Point2f>{p1}, n1, camera1.K, camera1.distortion);
    cv::undistortPoints(std::vector<cv::Point2f>{p2}, n2, camera2.K, camera2.distortion);
    const cv::Vec3d x1(n1[0].x, n1[0].y, 1.0), x2(n2[0].x, n2[0].y, 1.0);
    const cv::Vec3d l2 = E * x1;      // line of x2 in image 2
    const cv::Vec3d l1 = E.t() * x2;  // line of x1 in image 1
    const double d2 = std::abs(l2.dot(x2)) / std::hypot(l2[0], l2[1]);
    const double d1 = std::abs(l1.dot(x1)) / std::hypot(l1[0], l1[1]);
    return std::max(d1, d2) * focal <= tolerance;
  };
}

}  // namespace evaluation
}  // namespace enhanced_orb
