#include "enhanced_orb/evaluation/sequence.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <opencv2/calib3d.hpp>

#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/evaluation/degrade.h"

namespace enhanced_orb {
namespace evaluation {
namespace {

namespace fs = std::filesystem;

[[noreturn]] void fail(const std::string& what) {
  throw DatasetError(what);
}

// The 12 numbers after `key` on a line of a KITTI calib.txt ("P0: ..."), as a 3x4 matrix.
std::optional<cv::Matx34d> kittiProjection(const std::string& file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(key + ":", 0) != 0) {
      continue;
    }
    std::istringstream values(line.substr(key.size() + 1));
    cv::Matx34d P;
    for (int i = 0; i < 12; ++i) {
      if (!(values >> P.val[i])) {
        fail(file + ": " + key + " needs 12 numbers");
      }
    }
    return P;
  }
  return std::nullopt;
}

cv::Matx44d translation(double x, double y, double z) {
  cv::Matx44d T = cv::Matx44d::eye();
  T(0, 3) = x;
  T(1, 3) = y;
  T(2, 3) = z;
  return T;
}

// The rotation angle of R in degrees.
double angleDeg(const cv::Matx33d& R) {
  const double c = std::clamp((cv::trace(R) - 1.0) / 2.0, -1.0, 1.0);
  return std::acos(c) * 180.0 / CV_PI;
}

// Camera 2 relative to camera 1 of one rig: x2 = T_21 x1.
cv::Matx44d rigTransform(const Camera& camera1, const Camera& camera2) {
  return camera2.T_BS.inv() * camera1.T_BS;
}

// The folder's own name, also when `dir` ends in a separator ("kitti/turn_51/" is turn_51).
std::string folderName(const std::string& dir) {
  fs::path p = fs::path(dir).lexically_normal();
  if (p.filename().empty()) {
    p = p.parent_path();
  }
  return p.filename().string();
}

}  // namespace

Sequence readEurocSequence(const std::string& dir) {
  const EurocSequence left = readEuroc(dir, "cam0");
  if (!left.camera) {
    fail(left.mav0 + "/cam0/sensor.yaml: missing or without intrinsics, distortion_coefficients and T_BS");
  }
  if (!left.trajectory) {
    fail(left.mav0 + "/state_groundtruth_estimate0/data.csv: missing or without poses");
  }
  Sequence seq;
  seq.name = folderName(dir);
  if (seq.name.empty() || seq.name == "mav0") {
    seq.name = fs::path(left.mav0).parent_path().filename().string();
  }
  seq.format = "euroc";
  seq.left = *left.camera;
  std::map<std::int64_t, std::string> right_by_stamp;
  if (fs::is_regular_file(fs::path(left.mav0) / "cam1" / "data.csv")) {
    const EurocSequence right = readEuroc(dir, "cam1");
    if (right.camera) {
      seq.right = right.camera;
      for (const FrameRef& f : right.frames) {
        right_by_stamp[f.stamp] = f.path;
      }
    }
  }
  for (const FrameRef& f : left.frames) {
    const auto pose = left.trajectory->interpolated(f.stamp);
    const auto right = right_by_stamp.find(f.stamp);
    if (!pose || (seq.right && right == right_by_stamp.end())) {
      continue;
    }
    seq.frames.push_back(f.path);
    seq.poses.push_back(*pose);
    if (seq.right) {
      seq.right_frames.push_back(right->second);
    }
  }
  if (left.frames.size() >= 2) {
    const double span_s = static_cast<double>(left.frames.back().stamp - left.frames.front().stamp) * 1e-9;
    if (span_s > 0.0) {
      seq.rate_hz = std::round(static_cast<double>(left.frames.size() - 1) / span_s);
    }
  }
  return seq;
}

Sequence readKittiSequence(const std::string& dir, const std::string& poses_file) {
  const fs::path root(dir);
  const std::string calib = (root / "calib.txt").string();
  if (!fs::is_regular_file(calib)) {
    fail(calib + ": does not exist");
  }
  const auto P0 = kittiProjection(calib, "P0");
  if (!P0) {
    fail(calib + ": no P0 line");
  }
  const auto P1 = kittiProjection(calib, "P1");
  Sequence seq;
  seq.name = folderName(dir);
  seq.format = "kitti";
  seq.rate_hz = 10.0;
  const cv::Matx33d K((*P0)(0, 0), 0, (*P0)(0, 2), 0, (*P0)(1, 1), (*P0)(1, 2), 0, 0, 1);
  // The body is the left camera; P1 = K [I | t] with t = (-fx * baseline, 0, 0) / fx.
  seq.left = Camera{K, {0, 0, 0, 0}, cv::Matx44d::eye()};
  const std::string poses_path = !poses_file.empty() ? poses_file : (root / "poses.txt").string();
  std::ifstream poses_in(poses_path);
  if (!poses_in) {
    fail(poses_path + ": does not exist (give the sequence's poses/NN.txt)");
  }
  std::vector<cv::Matx44d> poses;
  std::string line;
  for (int n = 1; std::getline(poses_in, line); ++n) {
    if (line.empty()) {
      continue;
    }
    std::istringstream values(line);
    cv::Matx44d T = cv::Matx44d::eye();
    for (int i = 0; i < 12; ++i) {
      if (!(values >> T.val[i])) {
        fail(poses_path + ":" + std::to_string(n) + ": expected 12 numbers");
      }
    }
    poses.push_back(T);
  }
  const std::vector<FrameRef> left = readImageFolder((root / "image_0").string());
  std::vector<FrameRef> right;
  if (P1 && fs::is_directory(root / "image_1")) {
    right = readImageFolder((root / "image_1").string());
    seq.right = Camera{K, {0, 0, 0, 0}, translation(-(*P1)(0, 3) / (*P1)(0, 0), 0, 0)};
  }
  const size_t n = std::min(left.size(), poses.size());
  for (size_t i = 0; i < n; ++i) {
    if (seq.right && i >= right.size()) {
      break;
    }
    seq.frames.push_back(left[i].path);
    seq.poses.push_back(poses[i]);
    if (seq.right) {
      seq.right_frames.push_back(right[i].path);
    }
  }
  return seq;
}

Sequence readSequence(const std::string& dir) {
  const fs::path root(dir);
  if (fs::is_regular_file(root / "calib.txt")) {
    return readKittiSequence(dir);
  }
  if (fs::is_regular_file(root / "cam0" / "data.csv") || fs::is_regular_file(root / "mav0" / "cam0" / "data.csv")) {
    return readEurocSequence(dir);
  }
  fail(dir + ": neither a EuRoC ASL folder (mav0/cam0/data.csv) nor a KITTI odometry sequence (calib.txt)");
}

std::vector<int> defaultGaps(double rate_hz) {
  std::vector<int> gaps;
  for (double seconds : {0.05, 0.25, 0.5}) {
    const int g = std::max(1, static_cast<int>(std::lround(seconds * rate_hz)));
    if (gaps.empty() || g > gaps.back()) {
      gaps.push_back(g);
    }
  }
  if (gaps.size() < 3) {  // at 10 Hz: 1, 3, 5
    gaps = {1, std::max(2, static_cast<int>(std::lround(0.3 * rate_hz))),
            std::max(3, static_cast<int>(std::lround(0.5 * rate_hz)))};
  }
  return gaps;
}

namespace {

// The frames [first, end) the dip darkens: frames 100-249 of 300, scaled to the sequence.
std::pair<int, int> dipFrames(int n_frames) {
  const double scale = n_frames / 300.0;
  return {static_cast<int>(std::lround(100 * scale)), static_cast<int>(std::lround(250 * scale))};
}

// The lamp's light on the scene: kLampEdge + kLampPeak at the image centre, falling off as a Gaussian
// of kLampSigma x the image diagonal to kLampEdge (a dark room's light) at the edges.
constexpr double kLampEdge = 0.03;
constexpr double kLampPeak = 1.17;
constexpr double kLampSigma = 0.18;

constexpr double kMaxGain = 8.0;    // auto gain's cap
constexpr double kGainRate = 0.25;  // of the way to the target gain per frame, in log

std::string number(double x) {
  std::ostringstream s;
  s << x;
  return s.str();
}

std::string factor(double x) {
  return "x" + number(x);
}

}  // namespace

double LightCondition::light(int frame, int n_frames) const {
  const double t = n_frames > 1 ? static_cast<double>(frame) / (n_frames - 1) : 0.0;
  if (name == "unchanged" || name == "lamp") {
    return 1.0;  // lamp: the field does it
  } else if (name == "dim") {
    return 0.25;
  } else if (name == "dark") {
    return 0.06;
  } else if (name == "dusk") {
    return std::exp(std::log(0.05) * t);
  } else if (name == "lights_out") {
    return frame < n_frames / 2 ? 1.0 : 0.1;
  } else if (name == "flicker") {
    return frame % 2 == 0 ? 1.0 : 0.5;
  } else if (name == "dip") {
    const auto [first, end] = dipFrames(n_frames);
    return frame >= first && frame < end ? 0.02 : 1.0;
  }
  throw std::invalid_argument("unknown light condition '" + name + "'");
}

double LightCondition::gain(int frame, int n_frames) const {
  if (name == "dim") {
    return 2.0;
  } else if (name == "dark") {
    return 4.0;
  } else if (name == "dusk" || name == "lights_out" || name == "dip") {
    double g = std::clamp(1.0 / light(0, n_frames), 1.0, kMaxGain);
    for (int f = 1; f <= frame; ++f) {
      const double target = std::clamp(1.0 / light(f, n_frames), 1.0, kMaxGain);
      g *= std::pow(target / g, kGainRate);
    }
    return g;
  }
  light(frame, n_frames);  // rejects an unknown name
  return 1.0;
}

cv::Mat LightCondition::apply(const cv::Mat& gray, int frame, int n_frames, std::uint64_t seed) const {
  if (name == "unchanged") {
    return gray;
  }
  SensorModel sensor;
  sensor.gain = gain(frame, n_frames);
  if (name == "lamp") {
    // A lamp beside the camera, pointing where it looks (kLampPeak, kLampEdge).
    thread_local cv::Mat field;
    if (field.size() != gray.size()) {
      field.create(gray.size(), CV_32F);
      const double cx = 0.5 * gray.cols, cy = 0.5 * gray.rows;
      const double sigma = kLampSigma * std::hypot(gray.cols, gray.rows);
      for (int y = 0; y < gray.rows; ++y) {
        float* row = field.ptr<float>(y);
        for (int x = 0; x < gray.cols; ++x) {
          const double r2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
          row[x] = static_cast<float>(kLampEdge + kLampPeak * std::exp(-r2 / (2.0 * sigma * sigma)));
        }
      }
    }
    return lowLight(gray, field, 1.0, sensor, seed);
  }
  return lowLight(gray, cv::Mat(), light(frame, n_frames), sensor, seed);
}

std::string LightCondition::describe(int n_frames) const {
  const int last = n_frames - 1;
  const std::string of = " of " + std::to_string(n_frames);
  const std::string auto_gain = ", auto gain (up to " + number(kMaxGain) + ")";
  if (name == "unchanged") {
    return "as recorded";
  } else if (name == "dim" || name == "dark") {
    return factor(light(0, n_frames)) + ", gain " + number(gain(0, n_frames));
  } else if (name == "dusk") {
    return factor(light(0, n_frames)) + " to " + factor(light(last, n_frames)) + " over the sequence" + auto_gain;
  } else if (name == "lights_out") {
    return factor(light(n_frames / 2, n_frames)) + " from frame " + std::to_string(n_frames / 2) + of + " on" +
           auto_gain + ", catching up over ~10 frames";
  } else if (name == "flicker") {
    return "alternate frames " + factor(light(0, n_frames)) + " and " + factor(light(1, n_frames));
  } else if (name == "lamp") {
    return "a dark room (" + factor(kLampEdge) + ") lit by a lamp on the camera: " + factor(kLampEdge + kLampPeak) +
           " at the centre";
  } else if (name == "dip") {
    const auto [first, end] = dipFrames(n_frames);
    return factor(light(first, n_frames)) + " over frames " + std::to_string(first) + "-" + std::to_string(end - 1) +
           of + auto_gain;
  }
  light(0, n_frames);  // rejects an unknown name
  return name;
}

std::vector<LightCondition> lightConditions() {
  return {{"unchanged"}, {"dim"}, {"dark"}, {"dusk"}, {"lights_out"}, {"flicker"}, {"lamp"}, {"dip"}};
}

std::vector<StreamJudgment> judgeMotion(const std::vector<cv::Mat>& frames) {
  CameraMotion motion;
  std::vector<StreamJudgment> judged(frames.size());
  for (size_t i = 0; i < frames.size(); ++i) {
    judged[i] = motion.judge(frames[i]);
  }
  return judged;
}

RelativePose sequencePose(const Sequence& sequence, int i, int j) {
  return groundTruthPose(sequence.left, sequence.poses.at(i), sequence.left, sequence.poses.at(j));
}

StereoMap triangulateStereo(const Camera& left, const Camera& right, const std::vector<cv::KeyPoint>& kp_left,
                            const cv::Mat& d_left, const std::vector<cv::KeyPoint>& kp_right, const cv::Mat& d_right) {
  StereoMap map;
  const std::vector<cv::DMatch> matches = mutualMatches(d_left, d_right);
  map.stereo_matches = static_cast<int>(matches.size());
  if (matches.empty()) {
    return map;
  }
  std::vector<cv::Point2f> pl, pr;
  for (const cv::DMatch& m : matches) {
    pl.push_back(kp_left[m.queryIdx].pt);
    pr.push_back(kp_right[m.trainIdx].pt);
  }
  std::vector<cv::Point2f> nl, nr;
  cv::undistortPoints(pl, nl, left.K, left.distortion);
  cv::undistortPoints(pr, nr, right.K, right.distortion);
  const cv::Matx44d T_rl = rigTransform(left, right);
  const cv::Matx34d P_left = cv::Matx34d::eye();
  const cv::Matx34d P_right = T_rl.get_minor<3, 4>(0, 0);
  cv::Mat X;
  cv::triangulatePoints(P_left, P_right, nl, nr, X);
  const double fl = 0.5 * (left.K(0, 0) + left.K(1, 1));
  const double fr = 0.5 * (right.K(0, 0) + right.K(1, 1));
  constexpr double kMaxError = 2.0;  // pixels
  map.descriptors.create(0, d_left.cols, d_left.type());
  for (size_t k = 0; k < matches.size(); ++k) {
    const double w = X.at<float>(3, static_cast<int>(k));
    if (w == 0.0) {
      continue;
    }
    const cv::Vec3d xl(X.at<float>(0, static_cast<int>(k)) / w, X.at<float>(1, static_cast<int>(k)) / w,
                       X.at<float>(2, static_cast<int>(k)) / w);
    const cv::Vec4d h = T_rl * cv::Vec4d(xl[0], xl[1], xl[2], 1.0);
    const cv::Vec3d xr(h[0], h[1], h[2]);
    if (!(xl[2] > 0.1 && xl[2] < 40.0 && xr[2] > 0.1 && xr[2] < 40.0)) {
      continue;
    }
    const double el = std::hypot(xl[0] / xl[2] - nl[k].x, xl[1] / xl[2] - nl[k].y) * fl;
    const double er = std::hypot(xr[0] / xr[2] - nr[k].x, xr[1] / xr[2] - nr[k].y) * fr;
    if (el > kMaxError || er > kMaxError) {
      continue;
    }
    map.points.emplace_back(static_cast<float>(xl[0]), static_cast<float>(xl[1]), static_cast<float>(xl[2]));
    map.descriptors.push_back(d_left.row(matches[k].queryIdx));
  }
  return map;
}

TrackResult trackFrame(const StereoMap& map, const Camera& camera, const std::vector<cv::KeyPoint>& keypoints,
                       const cv::Mat& descriptors, const RelativePose& truth) {
  TrackResult result;
  const std::vector<cv::DMatch> matches = mutualMatches(map.descriptors, descriptors);
  result.matches = static_cast<int>(matches.size());
  if (matches.size() < 6) {
    return result;
  }
  std::vector<cv::Point3f> object;
  std::vector<cv::Point2f> image;
  for (const cv::DMatch& m : matches) {
    object.push_back(map.points[m.queryIdx]);
    image.push_back(keypoints[m.trainIdx].pt);
  }
  cv::theRNG().state = 0x2545F4914F6CDD1DULL;  // the same RANSAC samples for every method
  cv::Mat rvec, tvec;
  std::vector<int> inliers;
  result.solved = cv::solvePnPRansac(object, image, cv::Mat(camera.K), camera.distortion, rvec, tvec, false, 200, 2.0,
                                     0.999, inliers, cv::SOLVEPNP_ITERATIVE);
  result.inliers = static_cast<int>(inliers.size());
  if (!result.solved) {
    return result;
  }
  cv::Matx33d R;
  cv::Rodrigues(rvec, R);
  const cv::Vec3d t(tvec.at<double>(0), tvec.at<double>(1), tvec.at<double>(2));
  result.rotation_deg = angleDeg(R.t() * truth.R);
  result.translation_m = cv::norm(t - truth.t);
  return result;
}

}  // namespace evaluation
}  // namespace enhanced_orb
