#include <gtest/gtest.h>

#include "../../src/tools/evaluation.h"

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
