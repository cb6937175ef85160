#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/draw.h"
#include "enhanced_orb/orb_extractor.h"
#include "test_images.h"

using namespace enhanced_orb;

namespace {

// Pixels of `drawn` that differ from the plain image.
double paintedShare(const cv::Mat& gray, const cv::Mat& drawn) {
  cv::Mat plain, diff;
  cv::cvtColor(gray, plain, cv::COLOR_GRAY2BGR);
  cv::absdiff(plain, drawn, diff);
  cv::Mat any;
  cv::transform(diff, any, cv::Matx13f(1, 1, 1));
  return static_cast<double>(cv::countNonZero(any)) / static_cast<double>(gray.total());
}

}  // namespace

TEST(Draw, KeypointsGridAndTextAreDrawnInOctaveColours) {
  const cv::Mat gray(200, 300, CV_8UC1, cv::Scalar(0));
  const std::vector<cv::KeyPoint> kps = {cv::KeyPoint(100.0f, 100.0f, 31.0f, 0.0f, 1.0f, 0),
                                         cv::KeyPoint(200.0f, 100.0f, 37.2f, 90.0f, 1.0f, 2)};
  const cv::Mat thresholds(5, 5, CV_32S, cv::Scalar(7));
  DrawOptions none{false, false, false, false, 300};
  const cv::Mat blank = drawAnnotated(gray, kps, thresholds, "caption", none);
  ASSERT_EQ(blank.type(), CV_8UC3);
  ASSERT_EQ(blank.size(), gray.size());
  EXPECT_EQ(cv::countNonZero(blank.reshape(1)), 0);

  const cv::Mat drawn = drawAnnotated(gray, kps, thresholds, "", DrawOptions{true, true, false, false, 300});
  auto at = [](const cv::Scalar& c) { return cv::Vec3b(c[0], c[1], c[2]); };
  EXPECT_EQ(drawn.at<cv::Vec3b>(100, 100), at(octaveColour(0)));  // the dot
  EXPECT_EQ(drawn.at<cv::Vec3b>(100, 104), at(octaveColour(0)));  // the tick runs right (angle 0)
  EXPECT_EQ(drawn.at<cv::Vec3b>(105, 200), at(octaveColour(2)));  // and down (90)
  EXPECT_EQ(drawn.at<cv::Vec3b>(100, 110), cv::Vec3b(0, 0, 0));   // marks are small
  EXPECT_NE(octaveColour(0), octaveColour(1));

  const cv::Mat grid = drawAnnotated(gray, {}, thresholds, "", DrawOptions{false, false, true, false, 300});
  EXPECT_EQ(grid.at<cv::Vec3b>(100, 60), cv::Vec3b(255, 255, 255));  // cell border at x = 60
  const cv::Mat text = drawAnnotated(gray, {}, thresholds, "12 keypoints", DrawOptions{false, false, false, true, 300});
  EXPECT_GT(cv::countNonZero(text.reshape(1)), 50);
}

TEST(Draw, AtMostMaxDrawnKeypointsAreDrawn) {
  const cv::Mat gray(240, 320, CV_8UC1, cv::Scalar(0));
  std::vector<cv::KeyPoint> kps;
  for (int i = 0; i < 1000; ++i) {
    kps.emplace_back(cv::Point2f(10.0f + (i * 7) % 300, 10.0f + (i * 13) % 220), 31.0f, 0.0f, 1.0f + i % 17, 0);
  }
  const DrawOptions few{true, false, false, false, 50};
  const DrawOptions all{true, false, false, false, 0};
  EXPECT_LT(paintedShare(gray, drawAnnotated(gray, kps, cv::Mat(), "", few)),
            paintedShare(gray, drawAnnotated(gray, kps, cv::Mat(), "", all)) / 5.0);
}

TEST(Draw, DefaultSettingsLeaveMostOfAEurocFrameVisible) {
  cv::Mat frame = test::eurocFrame();
  if (frame.empty()) {
    frame = test::syntheticScene(cv::Size(752, 480), 400);
  }
  const Extraction r = OrbExtractor().extract(frame);
  ASSERT_EQ(r.keypoints.size(), 1000u);
  DrawOptions options;
  options.grid = true;
  const cv::Mat drawn = drawAnnotated(r.image, r.keypoints, r.cell_thresholds,
                                      "1000 keypoints (300 drawn) | lambda 0.21 | tone curve on | 9.1 ms", options);
  const double share = paintedShare(r.image, drawn);
  RecordProperty("painted_share_percent", static_cast<int>(share * 100));
  EXPECT_LT(share, 1.0 / 3.0);
  EXPECT_GT(share, 0.001);  // and something is drawn
}
