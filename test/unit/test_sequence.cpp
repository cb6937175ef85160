// The sequence evaluation: datasets as their publishers ship them, light over a sequence, the
// stereo tracking test and ORB-SLAM's quadtree, on data whose answer is known.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <tuple>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/evaluation/orb_slam_style.h"
#include "enhanced_orb/evaluation/sequence.h"
#include "shared_data.h"

namespace ev = enhanced_orb::evaluation;
namespace fs = std::filesystem;

namespace {

// A fresh folder under the system's temporary folder, removed at the end of the test.
struct TempDir {
  fs::path path;
  TempDir() {
    path = fs::temp_directory_path() / ("enhanced_orb_sequence_" + std::to_string(::getpid()) + "_" +
                                        std::to_string(reinterpret_cast<std::uintptr_t>(this)));
    fs::create_directories(path);
  }
  ~TempDir() { fs::remove_all(path); }
};

void write(const fs::path& file, const std::string& text) {
  fs::create_directories(file.parent_path());
  std::ofstream(file) << text;
}

// EuRoC's cam0/sensor.yaml as ETH ships it: no %YAML line, a comment after a value, a matrix
// written over several lines.
const char* const kEurocSensorYaml = R"(# General sensor definitions.
sensor_type: camera
comment: VI-Sensor cam0 (MT9M034)

# Sensor extrinsics wrt. the body-frame.
T_BS:
  cols: 4
  rows: 4
  data: [1.0, 0.0, 0.0, 0.5,
         0.0, 1.0, 0.0, 0.0,
         0.0, 0.0, 1.0, 0.0,
         0.0, 0.0, 0.0, 1.0]

rate_hz: 20
resolution: [752, 480]
camera_model: pinhole
intrinsics: [458.654, 457.296, 367.215, 248.375] #fu, fv, cu, cv
distortion_model: radial-tangential
distortion_coefficients: [-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05]
)";

ev::Camera pinhole() {
  ev::Camera cam;
  cam.K = cv::Matx33d(450, 0, 376, 0, 450, 240, 0, 0, 1);
  cam.distortion = {0, 0, 0, 0};
  cam.T_BS = cv::Matx44d::eye();
  return cam;
}

cv::Point2f project(const ev::Camera& cam, const cv::Vec3d& X) {
  const cv::Vec3d x = cam.K * X;
  return {static_cast<float>(x[0] / x[2]), static_cast<float>(x[1] / x[2])};
}

}  // namespace

TEST(Sequence, ReadsEurocSensorYamlAsEthShipsIt) {
  TempDir dir;
  write(dir.path / "mav0" / "cam0" / "sensor.yaml", kEurocSensorYaml);
  const auto cam = ev::readCamera((dir.path / "mav0").string(), "cam0");
  ASSERT_TRUE(cam.has_value());
  EXPECT_DOUBLE_EQ(cam->K(0, 0), 458.654);
  EXPECT_DOUBLE_EQ(cam->K(1, 2), 248.375);
  EXPECT_DOUBLE_EQ(cam->distortion[0], -0.28340811);
  EXPECT_DOUBLE_EQ(cam->T_BS(0, 3), 0.5);
  write(dir.path / "mav0" / "cam1" / "sensor.yaml", "intrinsics: [1, 2]\n");
  EXPECT_FALSE(ev::readCamera((dir.path / "mav0").string(), "cam1").has_value());
}

TEST(Sequence, EurocSequenceWithPosesAtTheFrameTimes) {
  TempDir dir;
  const fs::path mav0 = dir.path / "mav0";
  write(mav0 / "cam0" / "sensor.yaml", kEurocSensorYaml);
  write(mav0 / "cam1" / "sensor.yaml", kEurocSensorYaml);
  std::string csv = "#timestamp [ns],filename\n";
  const cv::Mat image(48, 64, CV_8U, cv::Scalar(100));
  for (int i = 0; i < 3; ++i) {
    const std::string name = std::to_string(1000000000LL + i * 50000000LL) + ".png";
    csv += std::to_string(1000000000LL + i * 50000000LL) + "," + name + "\n";
    for (const char* cam : {"cam0", "cam1"}) {
      fs::create_directories(mav0 / cam / "data");
      cv::imwrite((mav0 / cam / "data" / name).string(), image);
    }
  }
  write(mav0 / "cam0" / "data.csv", csv);
  write(mav0 / "cam1" / "data.csv", csv);
  // The body moves 1 m along x per second and turns 0.2 rad about z per second; poses every 30 ms,
  // so the frame times fall between them.
  std::string gt = "#timestamp, p_RS_R_x [m], p_RS_R_y [m], p_RS_R_z [m], q_RS_w [], q_RS_x [], q_RS_y [], q_RS_z []\n";
  for (int k = 0; k < 10; ++k) {
    const double t = 0.97 + 0.03 * k;
    const double half = 0.1 * t;
    gt += std::to_string(static_cast<long long>(std::llround(t * 1e9))) + "," + std::to_string(t) + ",0,0," +
          std::to_string(std::cos(half)) + ",0,0," + std::to_string(std::sin(half)) + "\n";
  }
  write(mav0 / "state_groundtruth_estimate0" / "data.csv", gt);
  const ev::Sequence seq = ev::readSequence(dir.path.string());
  EXPECT_EQ(seq.format, "euroc");
  EXPECT_EQ(seq.name, dir.path.filename().string());
  EXPECT_EQ(ev::readSequence(dir.path.string() + "/").name, seq.name);
  ASSERT_EQ(seq.frames.size(), 3u);
  ASSERT_EQ(seq.right_frames.size(), 3u);
  EXPECT_DOUBLE_EQ(seq.rate_hz, 20.0);
  EXPECT_NEAR(seq.poses[1](0, 3), 1.05, 1e-6);  // interpolated between 1.03 and 1.06
  EXPECT_NEAR(std::atan2(seq.poses[1](1, 0), seq.poses[1](0, 0)), 0.21, 1e-6);
  // Frame 0 to 2: the camera (0.5 m ahead of the body on x) turned 0.02 rad and moved.
  const ev::RelativePose rel = ev::sequencePose(seq, 0, 2);
  cv::Vec3d w;
  cv::Rodrigues(rel.R, w);
  EXPECT_NEAR(cv::norm(w), 0.02, 1e-6);
  fs::remove(mav0 / "state_groundtruth_estimate0" / "data.csv");
  EXPECT_THROW(ev::readSequence(dir.path.string()), ev::DatasetError);
}

TEST(Sequence, KittiSequenceWithItsBaseline) {
  TempDir dir;
  write(dir.path / "calib.txt", "P0: 700 0 600 0 0 700 180 0 0 0 1 0\nP1: 700 0 600 -378 0 700 180 0 0 0 1 0\n");
  std::string poses;
  for (int i = 0; i < 4; ++i) {
    poses += "1 0 0 0 0 1 0 0 0 0 1 " + std::to_string(0.8 * i) + "\n";
    for (const char* folder : {"image_0", "image_1"}) {
      fs::create_directories(dir.path / folder);
      cv::imwrite((dir.path / folder / ("00000" + std::to_string(i) + ".png")).string(), cv::Mat(20, 30, CV_8U));
    }
  }
  write(dir.path / "poses.txt", poses);
  const ev::Sequence seq = ev::readSequence(dir.path.string());
  EXPECT_EQ(seq.format, "kitti");
  EXPECT_EQ(seq.name, dir.path.filename().string());
  // A folder given with a separator at its end (as a shell's glob lists it) keeps its name.
  EXPECT_EQ(ev::readSequence(dir.path.string() + "/").name, seq.name);
  ASSERT_EQ(seq.frames.size(), 4u);
  ASSERT_TRUE(seq.right.has_value());
  EXPECT_NEAR(seq.right->T_BS(0, 3), 0.54, 1e-12);  // 378 / 700 m to the right
  EXPECT_DOUBLE_EQ(seq.rate_hz, 10.0);
  EXPECT_EQ(ev::defaultGaps(10.0), (std::vector<int>{1, 3, 5}));
  EXPECT_EQ(ev::defaultGaps(20.0), (std::vector<int>{1, 5, 10}));
  const ev::RelativePose rel = ev::sequencePose(seq, 1, 3);
  EXPECT_NEAR(rel.t[2], -1.6, 1e-9);  // the scene comes 1.6 m closer
}

TEST(Sequence, LightConditionsOverASequence) {
  const cv::Mat frame(60, 80, CV_8U, cv::Scalar(160));
  const int n = 300;
  auto mean = [&](const std::string& name, int i) {
    return cv::mean(ev::LightCondition{name}.apply(frame, i, n, 7))[0];
  };
  EXPECT_EQ(mean("unchanged", 10), 160.0);
  EXPECT_NEAR(mean("dim", 10), 80.0, 2.0);  // x0.25, gain 2
  EXPECT_NEAR(mean("flicker", 11), 80.0, 2.0);
  EXPECT_NEAR(mean("flicker", 12), 160.0, 2.0);
  // Lights out: dark at once, then the auto gain brings most of it back within about 10 frames.
  const ev::LightCondition out{"lights_out"};
  EXPECT_DOUBLE_EQ(out.gain(149, n), 1.0);
  EXPECT_LT(mean("lights_out", 150), 30.0);
  EXPECT_GT(out.gain(160, n), 6.0);
  EXPECT_GT(mean("lights_out", 165), 110.0);
  // Dusk: the light falls to x0.05, the gain follows up to its cap of 8.
  const ev::LightCondition dusk{"dusk"};
  EXPECT_NEAR(dusk.light(n - 1, n), 0.05, 1e-9);
  EXPECT_NEAR(dusk.gain(n - 1, n), 8.0, 0.1);
  EXPECT_NEAR(mean("dip", 200), 0.02 * 8.0 * 160.0, 3.0);
  // The lamp: bright in the middle, dark at the edges.
  const cv::Mat lamp = ev::LightCondition{"lamp"}.apply(frame, 0, n, 1);
  EXPECT_GT(lamp.at<uchar>(30, 40), 150);
  EXPECT_LT(lamp.at<uchar>(0, 0), 40);
  // Each frame its own noise, the same for the same seed.
  const cv::Mat a = ev::LightCondition{"dark"}.apply(frame, 5, n, 1);
  EXPECT_EQ(cv::norm(a, ev::LightCondition{"dark"}.apply(frame, 5, n, 1), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a, ev::LightCondition{"dark"}.apply(frame, 5, n, 2), cv::NORM_INF), 0.0);
  EXPECT_THROW(ev::LightCondition{"eclipse"}.apply(frame, 0, n, 1), std::invalid_argument);
  EXPECT_EQ(ev::lightConditions().size(), 8u);
}

// The legend states the frames and factors light() and gain() use, for the sequence's own length.
TEST(Sequence, LightConditionsDescribeTheFramesAndFactorsTheyApply) {
  const ev::LightCondition dip{"dip"};
  for (const auto& [n, first, last] : {std::tuple{300, 100, 249}, std::tuple{51, 17, 42}}) {
    EXPECT_EQ(dip.light(first - 1, n), 1.0);
    EXPECT_EQ(dip.light(first, n), 0.02);
    EXPECT_EQ(dip.light(last, n), 0.02);
    EXPECT_EQ(dip.light(last + 1, n), 1.0);
    const std::string frames =
        "frames " + std::to_string(first) + "-" + std::to_string(last) + " of " + std::to_string(n);
    EXPECT_NE(dip.describe(n).find("x0.02 over " + frames), std::string::npos) << dip.describe(n);
  }
  const ev::LightCondition out{"lights_out"};
  EXPECT_EQ(out.light(24, 51), 1.0);
  EXPECT_EQ(out.light(25, 51), 0.1);
  EXPECT_NE(out.describe(51).find("x0.1 from frame 25 of 51 on"), std::string::npos) << out.describe(51);
  EXPECT_EQ(ev::LightCondition{"dim"}.describe(300), "x0.25, gain 2");
  EXPECT_EQ(ev::LightCondition{"dark"}.describe(51), "x0.06, gain 4");
  EXPECT_EQ(ev::LightCondition{"flicker"}.describe(51), "alternate frames x1 and x0.5");
  EXPECT_NE(ev::LightCondition{"dusk"}.describe(51).find("x1 to x0.05 over the sequence"), std::string::npos);
  EXPECT_NE(ev::LightCondition{"lamp"}.describe(51).find("(x0.03)"), std::string::npos);
  EXPECT_EQ(ev::LightCondition{"unchanged"}.describe(51), "as recorded");
  EXPECT_THROW(ev::LightCondition{"eclipse"}.describe(300), std::invalid_argument);
}

TEST(Sequence, StereoTrackingRecoversAKnownMotionAndFailsOnWrongMatches) {
  const ev::Camera left = pinhole();
  ev::Camera right = pinhole();
  cv::Matx44d T = cv::Matx44d::eye();
  T(0, 3) = 0.11;  // EuRoC's baseline
  right.T_BS = T;
  cv::Matx33d R;
  cv::Rodrigues(cv::Vec3d(0.002, -0.004, 0.003), R);
  const ev::RelativePose motion{R, cv::Vec3d(0.01, -0.005, 0.02)};
  cv::RNG rng(5);
  std::vector<cv::KeyPoint> kl, kr, kn;
  cv::Mat dl(200, 32, CV_8U), dn;
  cv::randu(dl, 0, 256);
  for (int i = 0; i < 200; ++i) {
    const cv::Vec3d X(rng.uniform(-3.0, 3.0), rng.uniform(-2.0, 2.0), rng.uniform(2.0, 10.0));
    kl.emplace_back(project(left, X), 31.0f);
    kr.emplace_back(project(left, X - cv::Vec3d(0.11, 0, 0)), 31.0f);
    kn.emplace_back(project(left, motion.R * X + motion.t), 31.0f);
  }
  const ev::StereoMap map = ev::triangulateStereo(left, right, kl, dl, kr, dl.clone());
  EXPECT_EQ(map.stereo_matches, 200);
  EXPECT_EQ(map.points.size(), 200u);
  const ev::TrackResult good = ev::trackFrame(map, left, kn, dl.clone(), motion);
  EXPECT_TRUE(good.tracked());
  EXPECT_LT(good.rotation_deg, 0.01);
  EXPECT_LT(good.translation_m, 1e-3);
  // The same frame with the descriptors of other points: no motion agrees with the matches.
  cv::Mat shuffled = dl.clone();
  cv::randShuffle(shuffled, 1.0, &rng);
  EXPECT_FALSE(ev::trackFrame(map, left, kn, shuffled, motion).tracked());
  // A right image whose points do not triangulate (a disparity of the wrong sign) gives no map.
  const ev::StereoMap none = ev::triangulateStereo(left, right, kr, dl, kl, dl.clone());
  EXPECT_EQ(none.points.size(), 0u);
  EXPECT_FALSE(ev::trackFrame(none, left, kn, dl, motion).tracked());
}

TEST(OrbSlamStyle, QuadtreeSpreadsTheBudgetAndKeepsEachNodesStrongest) {
  std::vector<cv::KeyPoint> kps;
  for (int i = 0; i < 100; ++i) {  // a cluster in one corner, strong
    kps.emplace_back(cv::Point2f(5.0f + (i % 10) * 0.5f, 5.0f + (i / 10) * 0.5f), 7.0f, -1.0f, 100.0f + i);
  }
  for (int i = 0; i < 12; ++i) {  // weak corners spread over the rest
    kps.emplace_back(cv::Point2f(50.0f + 45.0f * (i % 4), 40.0f + 50.0f * (i / 4)), 7.0f, -1.0f, 10.0f);
  }
  const std::vector<cv::KeyPoint> kept = ev::distributeQuadtree(kps, cv::Rect2f(0, 0, 240, 200), 20);
  EXPECT_LE(kept.size(), 20u);
  EXPECT_GE(kept.size(), 16u);
  int spread = 0;
  float best = 0.0f;
  for (const cv::KeyPoint& kp : kept) {
    spread += kp.response == 10.0f;
    best = std::max(best, kp.response);
  }
  // The lone corners get nodes of their own (the strongest 20 alone would all be the cluster's);
  // the last split may leave two in one node.
  EXPECT_GE(spread, 10);
  EXPECT_EQ(best, 199.0f);  // the cluster's node keeps its strongest
  EXPECT_TRUE(ev::distributeQuadtree(kps, cv::Rect2f(0, 0, 240, 200), 0).empty());
}

TEST(OrbSlamStyle, ExtractsAtMostTheBudgetWithCvOrbDescriptors) {
  cv::Mat image(240, 320, CV_8U);
  cv::RNG rng(9);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  cv::GaussianBlur(image, image, cv::Size(5, 5), 1.5);
  ev::OrbSlamStyleParams p;
  p.n_features = 300;
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  ev::OrbSlamStyleExtractor(p).extract(image, kps, desc);
  EXPECT_GT(kps.size(), 200u);
  EXPECT_LE(kps.size(), 300u);
  EXPECT_EQ(desc.rows, static_cast<int>(kps.size()));
  EXPECT_EQ(desc.cols, 32);
  int octaves = 0;
  for (const cv::KeyPoint& kp : kps) {
    octaves = std::max(octaves, kp.octave);
  }
  EXPECT_GT(octaves, 2);
  ev::OrbSlamStyleExtractor(p).extract(cv::Mat(), kps, desc);
  EXPECT_TRUE(kps.empty());
}

#ifdef ENHANCED_ORB_MOVING_DIR
// The shared moving EuRoC excerpt, read with its files exactly as ETH ships them.
TEST(Sequence, ReadsTheMovingEurocExcerpt) {
  const std::string dir = ENHANCED_ORB_MOVING_DIR;
  REQUIRE_SHARED_DATA(fs::is_directory(dir), dir);
  const ev::Sequence seq = ev::readSequence(dir);
  EXPECT_EQ(seq.frames.size(), 300u);
  EXPECT_EQ(seq.right_frames.size(), 300u);
  EXPECT_DOUBLE_EQ(seq.rate_hz, 20.0);
  ASSERT_TRUE(seq.right.has_value());
  // The stereo baseline of EuRoC's rig, about 11 cm.
  const cv::Matx44d T = seq.right->T_BS.inv() * seq.left.T_BS;
  EXPECT_NEAR(cv::norm(cv::Vec3d(T(0, 3), T(1, 3), T(2, 3))), 0.11, 0.005);
  // The README: about 5.4 m of motion over the 300 frames.
  double path = 0.0;
  for (size_t i = 1; i < seq.poses.size(); ++i) {
    path += cv::norm(cv::Vec3d(seq.poses[i](0, 3) - seq.poses[i - 1](0, 3), seq.poses[i](1, 3) - seq.poses[i - 1](1, 3),
                               seq.poses[i](2, 3) - seq.poses[i - 1](2, 3)));
  }
  EXPECT_NEAR(path, 5.4, 0.6);
}
#endif
