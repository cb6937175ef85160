#include <gtest/gtest.h>

#include "enhanced_orb/draw.h"

using namespace enhanced_orb;

TEST(Draw, KeypointsGridAndTextAreDrawnInOctaveColours) {
  const cv::Mat gray(200, 300, CV_8UC1, cv::Scalar(0));
  const std::vector<cv::KeyPoint> kps = {cv::KeyPoint(100.0f, 100.0f, 31.0f, 0.0f, 1.0f, 0),
                                         cv::KeyPoint(200.0f, 100.0f, 37.2f, 90.0f, 1.0f, 1)};
  const cv::Mat thresholds(5, 5, CV_32S, cv::Scalar(7));
  DrawOptions none{false, false, false};
  const cv::Mat blank = drawAnnotated(gray, kps, thresholds, "caption", none);
  ASSERT_EQ(blank.type(), CV_8UC3);
  ASSERT_EQ(blank.size(), gray.size());
  EXPECT_EQ(cv::countNonZero(blank.reshape(1)), 0);

  const cv::Mat drawn = drawAnnotated(gray, kps, thresholds, "", DrawOptions{true, false, false});
  // The orientation line of the first keypoint runs right (angle 0), of the second down (90).
  auto at = [](const cv::Scalar& c) { return cv::Vec3b(c[0], c[1], c[2]); };
  EXPECT_EQ(drawn.at<cv::Vec3b>(100, 108), at(octaveColour(0)));
  EXPECT_EQ(drawn.at<cv::Vec3b>(108, 200), at(octaveColour(1)));
  EXPECT_EQ(drawn.at<cv::Vec3b>(100, 115), at(octaveColour(0)));  // on the circle of radius 15.5
  EXPECT_NE(octaveColour(0), octaveColour(1));

  const cv::Mat grid = drawAnnotated(gray, {}, thresholds, "", DrawOptions{false, true, false});
  EXPECT_EQ(grid.at<cv::Vec3b>(100, 60), cv::Vec3b(255, 255, 255));  // cell border at x = 60
  const cv::Mat text = drawAnnotated(gray, {}, thresholds, "12 keypoints", DrawOptions{false, false, true});
  EXPECT_GT(cv::countNonZero(text.reshape(1)), 50);
}
