#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include "enhanced_orb/evaluation/degrade.h"
#include "enhanced_orb/evaluation/files.h"
#include "enhanced_orb/evaluation/metrics.h"

namespace ev = enhanced_orb::evaluation;

using namespace enhanced_orb::evaluation;

namespace {

std::vector<cv::KeyPoint> points(const std::vector<cv::Point2f>& pts) {
  std::vector<cv::KeyPoint> kps;
  for (const auto& p : pts) {
    kps.emplace_back(p, 31.0f);
  }
  return kps;
}

}  // namespace

TEST(Evaluation, IdentityToleranceIsThreePixels) {
  const GroundTruth truth = identity();
  EXPECT_TRUE(truth({10, 10}, {12, 12}));   // 2.83 px
  EXPECT_FALSE(truth({10, 10}, {13, 12}));  // 3.6 px
}

TEST(Evaluation, RepeatabilityCountsTheSmallerSetOnce) {
  const auto a = points({{10, 10}, {50, 50}, {100, 100}, {200, 200}});
  const auto b = points({{11, 11}, {52, 49}, {300, 300}});
  EXPECT_DOUBLE_EQ(repeatability(a, b), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(repeatability(b, a), 2.0 / 3.0);
  // A cluster around one point of the smaller set does not push the share above 1.
  const auto cluster = points({{10, 10}, {10.5f, 10}, {11, 10}, {9.5f, 10}});
  EXPECT_DOUBLE_EQ(repeatability(cluster, points({{10, 11}})), 1.0);
  EXPECT_DOUBLE_EQ(repeatability(a, {}), 0.0);
}

TEST(Evaluation, MatchingCountsCorrectMatches) {
  cv::Mat d(3, 32, CV_8U);
  cv::randu(d, 0, 256);
  const auto kp1 = points({{10, 10}, {50, 50}, {90, 90}});
  const auto kp2 = points({{10, 10}, {50, 58}, {90, 91}});  // the second is 8 px off
  const MatchCounts c = matchAndCount(kp1, d, kp2, d.clone(), identity());
  EXPECT_EQ(c.matches, 3);
  EXPECT_EQ(c.correct, 2);
  EXPECT_NEAR(c.accuracy(), 2.0 / 3.0, 1e-12);
}

TEST(Evaluation, EpipolarGroundTruthOfASidewaysStep) {
  // A camera moving 0.1 m along its x axis: epipolar lines are image rows.
  Camera cam;
  cam.K = cv::Matx33d(400, 0, 320, 0, 400, 240, 0, 0, 1);
  cam.distortion = {0, 0, 0, 0};
  cam.T_BS = cv::Matx44d::eye();
  cv::Matx44d moved = cv::Matx44d::eye();
  moved(0, 3) = 0.1;
  const GroundTruth truth = epipolar(cam, cv::Matx44d::eye(), moved);
  EXPECT_TRUE(truth({300, 200}, {260, 201}));   // same row, 1 px off
  EXPECT_FALSE(truth({300, 200}, {260, 210}));  // 10 rows off
}

TEST(Pose, AucOfPerfectAndFailedEstimates) {
  EXPECT_DOUBLE_EQ(ev::poseAuc({0.0, 0.0}, 10.0), 1.0);
  EXPECT_DOUBLE_EQ(ev::poseAuc({180.0, 180.0}, 10.0), 0.0);
  EXPECT_NEAR(ev::poseAuc({5.0}, 10.0), 0.5, 1e-9);         // recall 1 from 5 degrees on
  EXPECT_NEAR(ev::poseAuc({0.0, 180.0}, 10.0), 0.5, 1e-9);  // half the pairs perfect
}

namespace {

// A 752x480 pinhole camera without distortion, and a small rotation, for the pose tests.
ev::Camera poseTestCamera() {
  ev::Camera cam;
  cam.K = cv::Matx33d(450, 0, 376, 0, 450, 240, 0, 0, 1);
  cam.distortion = {0, 0, 0, 0};
  cam.T_BS = cv::Matx44d::eye();
  return cam;
}

cv::Matx33d poseTestRotation() {
  cv::Matx33d R;
  cv::Rodrigues(cv::Vec3d(0.01, -0.02, 0.0175), R);
  return R;
}

}  // namespace

TEST(Pose, EstimateRecoversAKnownMotion) {
  const ev::Camera cam = poseTestCamera();
  const cv::Matx33d R = poseTestRotation();
  const cv::Vec3d t(0.3, 0.05, 0.02);
  cv::RNG rng(3);
  std::vector<cv::Point2f> p1, p2;
  for (int i = 0; i < 200; ++i) {
    const cv::Vec3d X(rng.uniform(-2.0, 2.0), rng.uniform(-1.5, 1.5), rng.uniform(3.0, 8.0));
    const cv::Vec3d Y = R * X + t;
    const cv::Vec3d a = cam.K * X, b = cam.K * Y;
    p1.emplace_back(a[0] / a[2], a[1] / a[2]);
    p2.emplace_back(b[0] / b[2], b[1] / b[2]);
  }
  const ev::PoseEstimate est = ev::estimatePose(cam, cam, p1, p2);
  ASSERT_TRUE(est.ok);
  const ev::PoseError err = ev::poseError(est, {R, t});
  EXPECT_LT(err.rotation_deg, 0.5);
  EXPECT_LT(err.translation_deg, 2.0);
  EXPECT_DOUBLE_EQ(ev::poseError(ev::PoseEstimate(), {R, t}).max(), 180.0);
}

TEST(Pose, DrawsTakeOtherSamplesAndTheMedianDrawIsKept) {
  const ev::Camera cam = poseTestCamera();
  const cv::Matx33d R = poseTestRotation();
  const cv::Vec3d t(0.05, 0.01, 0.3);  // forward, as a car drives: the pose's hard case
  cv::RNG rng(5);
  std::vector<cv::Point2f> p1, p2;
  for (int i = 0; i < 300; ++i) {
    const cv::Vec3d X(rng.uniform(-2.0, 2.0), rng.uniform(-1.5, 1.5), rng.uniform(3.0, 8.0));
    const cv::Vec3d Y = R * X + t;
    const cv::Vec3d a = cam.K * X, b = cam.K * Y;
    p1.emplace_back(static_cast<float>(a[0] / a[2] + rng.gaussian(0.7)),
                    static_cast<float>(a[1] / a[2] + rng.gaussian(0.7)));
    if (i % 3 == 0) {  // a third of the matches wrong
      p2.emplace_back(static_cast<float>(rng.uniform(0.0, 752.0)), static_cast<float>(rng.uniform(0.0, 480.0)));
    } else {
      p2.emplace_back(static_cast<float>(b[0] / b[2] + rng.gaussian(0.7)),
                      static_cast<float>(b[1] / b[2] + rng.gaussian(0.7)));
    }
  }
  const ev::RelativePose truth{R, t};
  std::vector<double> errors;
  for (int draw = 0; draw < 5; ++draw) {
    const ev::PoseEstimate est = ev::estimatePose(cam, cam, p1, p2, draw);
    ASSERT_TRUE(est.ok) << draw;
    errors.push_back(ev::poseError(est, truth).max());
  }
  // Draw 0 is the matches in their order, as estimatePose() takes them by default.
  EXPECT_EQ(ev::poseError(ev::estimatePose(cam, cam, p1, p2), truth).max(), errors[0]);
  // Another order gives the RANSAC other samples, and so another estimate.
  EXPECT_GT(*std::max_element(errors.begin(), errors.end()) - *std::min_element(errors.begin(), errors.end()), 0.0);
  std::vector<double> sorted = errors;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(ev::medianPoseOfDraws(cam, cam, p1, p2, truth, 5).error.max(), sorted[2]);
  std::vector<double> four(errors.begin(), errors.begin() + 4);
  std::sort(four.begin(), four.end());
  EXPECT_EQ(ev::medianPoseOfDraws(cam, cam, p1, p2, truth, 4).error.max(), four[1]);  // the lower middle
  EXPECT_EQ(ev::medianPoseOfDraws(cam, cam, p1, p2, truth, 1).error.max(), errors[0]);
  EXPECT_EQ(ev::medianPoseOfDraws(cam, cam, p1, p2, truth, 0).error.max(), errors[0]);
  EXPECT_LT(sorted[2], 5.0);  // the median draw finds the motion
}

TEST(Degrade, LowLightDarkensAndAddsSignalDependentNoise) {
  cv::Mat flat(100, 100, CV_8U, cv::Scalar(200));
  ev::SensorModel sensor;
  const cv::Mat dark = ev::lowLight(flat, cv::Mat(), 0.2, sensor, 1);
  cv::Scalar m, s;
  cv::meanStdDev(dark, m, s);
  EXPECT_NEAR(m[0], 40.0, 1.5);
  EXPECT_GT(s[0], 3.0);  // shot noise of 80 electrons at 2 per DN: about 4.5 DN
  EXPECT_EQ(cv::norm(dark, ev::lowLight(flat, cv::Mat(), 0.2, sensor, 1), cv::NORM_INF), 0.0);  // seeded
  EXPECT_THROW(ev::Degradation{"sunburn"}.apply(flat, 0), std::invalid_argument);
  for (const ev::Degradation& d : ev::standardDegradations()) {
    EXPECT_EQ(d.apply(flat, 2).size(), flat.size()) << d.name;
  }
}

TEST(Degrade, PhotometricChangesAreThePapersFormulas) {
  cv::Mat ramp(1, 256, CV_8U);
  for (int i = 0; i < 256; ++i) {
    ramp.at<uchar>(i) = static_cast<uchar>(i);
  }
  const cv::Mat darker = ev::changeBrightness(ramp, -0.6);
  EXPECT_EQ(darker.at<uchar>(100), 40);                            // 100 x 0.4
  EXPECT_EQ(ev::changeBrightness(ramp, 0.6).at<uchar>(200), 255);  // saturated
  const cv::Mat gamma = ev::applyGamma(ramp, 2.0);
  EXPECT_EQ(gamma.at<uchar>(0), 0);
  EXPECT_EQ(gamma.at<uchar>(255), 255);
  EXPECT_EQ(gamma.at<uchar>(64), 16);  // 255 (64/255)^2 = 16.06
  // The named EuRoC degradations are these changes.
  EXPECT_EQ(cv::norm(ev::Degradation{"dark"}.apply(ramp, 1), darker, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(ev::Degradation{"gamma_2"}.apply(ramp, 1), gamma, cv::NORM_INF), 0.0);
  // Noise: the same for a seed, another for another seed, none at sigma 0.
  const cv::Mat flat(64, 64, CV_8U, cv::Scalar(128));
  EXPECT_EQ(cv::norm(ev::addGaussianNoise(flat, 10, 7), ev::addGaussianNoise(flat, 10, 7), cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(ev::addGaussianNoise(flat, 10, 7), ev::addGaussianNoise(flat, 10, 8), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(ev::addGaussianNoise(flat, 0, 7), flat, cv::NORM_INF), 0.0);
  cv::Scalar mean, sd;
  cv::meanStdDev(ev::addGaussianNoise(flat, 10, 7), mean, sd);
  EXPECT_NEAR(sd[0], 10.0, 1.0);
  EXPECT_EQ(cv::norm(ev::Degradation{"noise_10"}.apply(flat, 7), ev::addGaussianNoise(flat, 10, 7), cv::NORM_INF), 0.0);
}

// A CSV file appears under its name only when committed, with what was written; an abandoned one
// leaves nothing, and a folder that does not exist is refused at once.
TEST(Files, AtomicTextFileAppearsOnlyWhenCommitted) {
  namespace fs = std::filesystem;
  const fs::path dir =
      fs::temp_directory_path() / ("eo_atomic_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string path = (dir / "table.csv").string();
  {
    AtomicTextFile abandoned(path);
    abandoned.out() << "half\n";
  }
  EXPECT_TRUE(fs::is_empty(dir)) << "an uncommitted file was left behind";
  {
    AtomicTextFile file(path);
    file.out() << "a,b\n1,2\n";
    EXPECT_FALSE(fs::exists(path));
    file.commit();
  }
  std::ifstream in(path);
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()), "a,b\n1,2\n");
  EXPECT_THROW(AtomicTextFile((dir / "missing" / "x.csv").string()), std::runtime_error);
  fs::remove_all(dir);
}
