// The drop-in adapters: enhanced_orb::ORB used as code written for cv::ORB uses it, and
// OrbSlamExtractor used as ORB-SLAM3 uses its ORBextractor.
#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/feature2d.h"
#include "enhanced_orb/orb_slam_extractor.h"
#include "test_images.h"

using namespace enhanced_orb;

namespace {

cv::Mat frame() {
  const cv::Mat euroc = test::eurocFrame();
  return euroc.empty() ? test::syntheticScene(cv::Size(752, 480)) : euroc;
}

void expectSameKeypoints(const std::vector<cv::KeyPoint>& a, const std::vector<cv::KeyPoint>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_TRUE(a[i].pt == b[i].pt && a[i].angle == b[i].angle && a[i].octave == b[i].octave &&
                a[i].size == b[i].size && a[i].response == b[i].response)
        << "keypoint " << i;
  }
}

// Code written against cv::Feature2D, as a cv::ORB user has it.
void detectAndDescribe(const cv::Ptr<cv::Feature2D>& detector, const cv::Mat& image, const cv::Mat& mask,
                       std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors) {
  detector->detectAndCompute(image, mask, keypoints, descriptors);
}

}  // namespace

TEST(Feature2D, GivesWhatExtractGivesThroughTheFeature2DInterface) {
  const cv::Mat image = frame();
  for (const char* preset : {"default", "paper", "motion", "stretch", "baseline"}) {
    Params params = presetParams(preset);
    params.orb.max_features = 1000;
    const Extraction expected = OrbExtractor(params).extract(image);
    cv::Ptr<cv::Feature2D> orb = ORB::create(params);
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    detectAndDescribe(orb, image, cv::Mat(), keypoints, descriptors);
    expectSameKeypoints(keypoints, expected.keypoints);
    EXPECT_EQ(cv::norm(descriptors, expected.descriptors, cv::NORM_INF), 0.0) << preset;
    EXPECT_EQ(orb->descriptorSize(), 32);
    EXPECT_EQ(orb->descriptorType(), CV_8U);
    EXPECT_EQ(orb->defaultNorm(), cv::NORM_HAMMING);
    EXPECT_EQ(orb->getDefaultName(), "Feature2D.EnhancedORB");
  }
  EXPECT_EQ(ORB::create("motion")->params().orb.noise_floor, Params::motion().orb.noise_floor);
  EXPECT_THROW(ORB::create("bogus"), std::invalid_argument);
}

TEST(Feature2D, NoKeypointWhereTheMaskIsZeroAndTheBudgetGoesElsewhere) {
  const cv::Mat image = frame();
  cv::Ptr<cv::Feature2D> orb = ORB::create();
  cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(255));
  mask(cv::Rect(0, 0, image.cols / 2, image.rows)).setTo(0);
  std::vector<cv::KeyPoint> all, masked;
  cv::Mat descriptors;
  orb->detect(image, all);
  orb->detectAndCompute(image, mask, masked, descriptors);
  ASSERT_GT(masked.size(), 500u);
  EXPECT_EQ(descriptors.rows, static_cast<int>(masked.size()));
  const auto left = [&](const cv::KeyPoint& kp) { return cvRound(kp.pt.x) < image.cols / 2; };
  EXPECT_EQ(std::count_if(masked.begin(), masked.end(), left), 0);
  // The masked half's share of the budget went to the other half.
  EXPECT_GT(static_cast<long>(masked.size()),
            std::count_if(all.begin(), all.end(), [&](const cv::KeyPoint& kp) { return !left(kp); }));
  EXPECT_THROW(orb->detect(image, masked, cv::Mat(10, 10, CV_8UC1, cv::Scalar(255))), cv::Exception);
  EXPECT_THROW(orb->detect(image, masked, cv::Mat(image.size(), CV_32F)), cv::Exception);
}

TEST(Feature2D, DetectThenComputeEqualsDetectAndCompute) {
  const cv::Mat image = frame();
  cv::Ptr<cv::Feature2D> orb = ORB::create();
  std::vector<cv::KeyPoint> together, apart;
  cv::Mat expected, descriptors;
  orb->detectAndCompute(image, cv::noArray(), together, expected);
  orb->detect(image, apart);
  orb->compute(image, apart, descriptors);
  expectSameKeypoints(apart, together);
  EXPECT_EQ(cv::norm(descriptors, expected, cv::NORM_INF), 0.0);
  // Keypoints that cannot be described are removed; the others keep their descriptors.
  std::vector<cv::KeyPoint> mixed = {together[0], cv::KeyPoint(2.f, 2.f, 31.f, 0.f, 10.f, 0), together[1],
                                     cv::KeyPoint(100.f, 100.f, 31.f, 0.f, 10.f, 12), together[2]};
  orb->compute(image, mixed, descriptors);
  ASSERT_EQ(mixed.size(), 3u);
  ASSERT_EQ(descriptors.rows, 3);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(cv::norm(descriptors.row(i), expected.row(i), cv::NORM_INF), 0.0) << i;
  }
}

TEST(Feature2D, WorksWithOpenCvsMatcherAndDrawingAndColourInput) {
  const cv::Mat image = frame();
  cv::Ptr<cv::Feature2D> orb = ORB::create();
  std::vector<cv::KeyPoint> keypoints, from_colour;
  cv::Mat descriptors, colour_descriptors;
  orb->detectAndCompute(image, cv::noArray(), keypoints, descriptors);
  cv::Mat bgr;
  cv::cvtColor(image, bgr, cv::COLOR_GRAY2BGR);
  orb->detectAndCompute(bgr, cv::noArray(), from_colour, colour_descriptors);
  expectSameKeypoints(from_colour, keypoints);
  cv::BFMatcher matcher(orb->defaultNorm(), true);
  std::vector<cv::DMatch> matches;
  matcher.match(descriptors, colour_descriptors, matches);
  ASSERT_EQ(matches.size(), keypoints.size());
  for (const cv::DMatch& m : matches) {
    EXPECT_EQ(m.distance, 0.f);
  }
  cv::Mat drawn;
  cv::drawKeypoints(bgr, keypoints, drawn);
  EXPECT_EQ(drawn.size(), image.size());
  EXPECT_GT(cv::norm(drawn, bgr, cv::NORM_L1), 0.0);
  EXPECT_THROW(orb->detect(cv::Mat(100, 100, CV_32F, cv::Scalar(0)), keypoints), cv::Exception);
  orb->detectAndCompute(cv::Mat(), cv::noArray(), keypoints, descriptors);
  EXPECT_TRUE(keypoints.empty());
  EXPECT_EQ(descriptors.rows, 0);
}

TEST(Feature2D, ParametersRoundTripThroughFileStorage) {
  Params motion = Params::motion();
  motion.enhance.alpha = 0.25;
  motion.orb.max_features = 777;
  cv::FileStorage out(".yml", cv::FileStorage::WRITE | cv::FileStorage::MEMORY);
  ORB::create(motion)->write(out);
  const std::string text = out.releaseAndGetString();
  cv::Ptr<ORB> read_back = ORB::create("paper");
  cv::FileStorage in(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  read_back->read(in.root());
  for (const std::string& name : paramNames()) {
    EXPECT_EQ(paramText(read_back->params(), name), paramText(motion, name)) << name;
  }
  cv::FileStorage bad("%YAML:1.0\nalpha: 7\n", cv::FileStorage::READ | cv::FileStorage::MEMORY);
  EXPECT_THROW(read_back->read(bad.root()), std::invalid_argument);
  EXPECT_EQ(read_back->params().orb.max_features, 777);  // unchanged by the failed read
}

TEST(Feature2D, ReadsThePackagesConfigFiles) {
  const std::string config = std::string(ENHANCED_ORB_SOURCE_DIR) + "/config/motion.yaml";
  const Params params = readParamsFile(config);
  Params expected = Params::motion();
  expected.orb.max_features = 1000;
  for (const std::string& name : paramNames()) {
    EXPECT_EQ(paramText(params, name), paramText(expected, name)) << name;
  }
  EXPECT_THROW(readParamsFile("/nonexistent.yaml"), std::invalid_argument);
}

namespace {

// Code written for ORB-SLAM3's ORBextractor (Frame::ExtractORB and what reads the extractor).
template <typename Extractor>
int extractLikeOrbSlam3(Extractor& extractor, const cv::Mat& image, std::vector<cv::KeyPoint>& keys,
                        cv::Mat& descriptors, int x0, int x1) {
  std::vector<int> lapping = {x0, x1};
  return extractor(image, cv::Mat(), keys, descriptors, lapping);
}

}  // namespace

TEST(OrbSlamExtractor, HasOrbSlam3sInterfaceAndOrdering) {
  const cv::Mat image = frame();
  OrbSlamExtractor extractor(1000, 1.2f, 8, 20, 7);
  EXPECT_EQ(extractor.params().orb.max_features, 1000);
  EXPECT_EQ(extractor.params().threshold.c_min, 7);
  EXPECT_EQ(extractor.params().orb.fast_threshold, 20);
  ASSERT_EQ(extractor.GetLevels(), 8);
  EXPECT_FLOAT_EQ(extractor.GetScaleFactor(), 1.2f);
  const std::vector<float> scales = extractor.GetScaleFactors();
  const std::vector<float> sigma2 = extractor.GetScaleSigmaSquares();
  for (int l = 0; l < 8; ++l) {
    EXPECT_FLOAT_EQ(scales[l], std::pow(1.2f, static_cast<float>(l)));
    EXPECT_FLOAT_EQ(extractor.GetInverseScaleFactors()[l] * scales[l], 1.f);
    EXPECT_FLOAT_EQ(sigma2[l], scales[l] * scales[l]);
    EXPECT_FLOAT_EQ(extractor.GetInverseScaleSigmaSquares()[l] * sigma2[l], 1.f);
  }
  std::vector<cv::KeyPoint> keys;
  cv::Mat descriptors;
  const int mono = extractLikeOrbSlam3(extractor, image, keys, descriptors, 300, 450);
  ASSERT_EQ(descriptors.rows, static_cast<int>(keys.size()));
  ASSERT_GT(mono, 0);
  ASSERT_LT(mono, static_cast<int>(keys.size()));
  for (int i = 0; i < static_cast<int>(keys.size()); ++i) {
    const bool inside = keys[i].pt.x >= 300 && keys[i].pt.x <= 450;
    EXPECT_EQ(inside, i >= mono) << i;
    EXPECT_FLOAT_EQ(keys[i].size, 31.f * scales[keys[i].octave]);
  }
  // The same keypoints and descriptors as extract() on a stream that starts moving, reordered.
  Params params = extractor.params();
  CameraMotion motion(CameraMotion::Start::kMoving);
  ExtractOptions options;
  Extraction expected;
  OrbExtractor(params).extract(image, motion, options, expected);
  EXPECT_TRUE(expected.camera_moving);
  ASSERT_EQ(expected.keypoints.size(), keys.size());
  int matched = 0;
  for (size_t i = 0; i < keys.size(); ++i) {
    for (size_t j = 0; j < expected.keypoints.size(); ++j) {
      if (expected.keypoints[j].pt == keys[i].pt && expected.keypoints[j].octave == keys[i].octave) {
        matched += cv::norm(descriptors.row(static_cast<int>(i)), expected.descriptors.row(static_cast<int>(j)),
                            cv::NORM_HAMMING) == 0;
        break;
      }
    }
  }
  EXPECT_EQ(matched, static_cast<int>(keys.size()));
  // The pyramid ORB-SLAM's stereo matching reads: the image the keypoints were found on, per level.
  ASSERT_EQ(extractor.mvImagePyramid.size(), 8u);
  EXPECT_EQ(cv::norm(extractor.mvImagePyramid[0], expected.image, cv::NORM_INF), 0.0);
  for (int l = 0; l < 8; ++l) {
    EXPECT_EQ(extractor.mvImagePyramid[l].cols, cvRound(image.cols / scales[l])) << l;
    EXPECT_EQ(extractor.mvImagePyramid[l].rows, cvRound(image.rows / scales[l])) << l;
  }
  const std::vector<cv::Mat> pyramid = buildPyramid(expected.image, 8, params.orb.scale_factor);
  EXPECT_EQ(cv::norm(extractor.mvImagePyramid[5], pyramid[5], cv::NORM_INF), 0.0);
  // ORB-SLAM2's call and an empty image.
  std::vector<cv::KeyPoint> keys2;
  cv::Mat descriptors2;
  extractor(image, cv::Mat(), keys2, descriptors2);
  EXPECT_EQ(keys2.size(), keys.size());
  EXPECT_EQ(extractLikeOrbSlam3(extractor, cv::Mat(), keys, descriptors, 0, 0), -1);
}

TEST(OrbSlamExtractor, TakesTheOtherParametersFromAFileOrAPreset) {
  const std::string config = std::string(ENHANCED_ORB_SOURCE_DIR) + "/config/motion.yaml";
  setenv("ENHANCED_ORB_CONFIG", config.c_str(), 1);
  OrbSlamExtractor from_file(1200, 1.2f, 8, 20, 7);
  unsetenv("ENHANCED_ORB_CONFIG");
  EXPECT_EQ(from_file.params().orb.noise_floor, Params::motion().orb.noise_floor);
  EXPECT_EQ(from_file.params().orb.max_features, 1200);  // ORB-SLAM's own settings win
  // In ORB-SLAM a moving camera's frames all get the tone curve, unless the file says otherwise.
  EXPECT_EQ(from_file.params().enhance.moving_gamma_mode, GammaMode::kAlways);
  EXPECT_EQ(OrbSlamExtractor(1000, 1.2f, 8, 20, 7).params().enhance.moving_gamma_mode, GammaMode::kAlways);
  EXPECT_EQ(Params().enhance.moving_gamma_mode, GammaMode::kNever);  // elsewhere the default mode's
  // The moving selection's cap on the corners above the floor is the preset's, unless the file sets it.
  EXPECT_EQ(from_file.params().orb.floor_candidate_ratio, Params::motion().orb.floor_candidate_ratio);
  EXPECT_EQ(OrbSlamExtractor(1000, 1.2f, 8, 20, 7).params().orb.floor_candidate_ratio,
            Params().orb.floor_candidate_ratio);
  EXPECT_GT(Params().orb.floor_candidate_ratio, 0.0);  // and the default mode caps them
  const std::string own = ::testing::TempDir() + "orb_slam_auto.yaml";
  std::ofstream(own) << "preset: default\nmoving_gamma_mode: auto\nc_min: 9\nfloor_candidate_ratio: 12\n";
  setenv("ENHANCED_ORB_CONFIG", own.c_str(), 1);
  OrbSlamExtractor auto_file(1000, 1.2f, 8, 20, 7);
  unsetenv("ENHANCED_ORB_CONFIG");
  EXPECT_EQ(auto_file.params().enhance.moving_gamma_mode, GammaMode::kAuto);
  EXPECT_EQ(auto_file.params().orb.floor_candidate_ratio, 12.0);
  EXPECT_EQ(auto_file.params().threshold.c_min, 7);  // minThFAST wins over the file
  std::vector<std::string> given;
  readParamsFile(own, Params(), &given);
  EXPECT_EQ(given, (std::vector<std::string>{"moving_gamma_mode", "c_min", "floor_candidate_ratio"}));
  OrbSlamExtractor paper(1000, 1.2f, 8, 20, 7, Params::paper());
  EXPECT_EQ(paper.params().enhance.tone_curve, Params::paper().enhance.tone_curve);
  EXPECT_THROW(OrbSlamExtractor(1000, 1.2f, 8, 20, 0), std::invalid_argument);  // c_min below 1
  EXPECT_THROW(OrbSlamExtractor(1000, 0.5f, 8, 20, 7), std::invalid_argument);
}
