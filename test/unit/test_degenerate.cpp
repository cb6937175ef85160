#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "enhanced_orb/orb_extractor.h"

using namespace enhanced_orb;

namespace {

std::vector<Params> allModes() {
  Params improved;
  Params always;
  always.enhance.gamma_mode = GammaMode::kAlways;
  Params budget;
  budget.orb.max_features = 500;
  Params parallel;
  parallel.orb.threads = 3;  // more threads than the rows of the smallest images
  Params paper_parallel = Params::paper();
  paper_parallel.orb.threads = 2;
  Params stretch = Params::stretch();
  stretch.enhance.gamma_mode = GammaMode::kAlways;  // the stretch curve on every image
  return {improved, always, budget, Params::baseline(), parallel, paper_parallel, stretch, Params::motion()};
}

void expectDefined(const Extraction& r, const cv::Mat& input, const Params& p) {
  EXPECT_EQ(r.image.size(), input.size());
  EXPECT_EQ(r.descriptors.rows, static_cast<int>(r.keypoints.size()));
  EXPECT_EQ(r.descriptors.cols, kDescriptorBytes);
  ASSERT_EQ(r.cell_thresholds.size(), cv::Size(p.threshold.grid_size, p.threshold.grid_size));
  EXPECT_EQ(r.cell_thresholds.type(), CV_32S);
  EXPECT_FALSE(r.level_thresholds.empty());
}

}  // namespace

TEST(Degenerate, ConstantImagesHaveNoKeypoints) {
  for (int value : {0, 255, 128}) {
    const cv::Mat image(480, 752, CV_8UC1, cv::Scalar(value));
    for (const Params& p : allModes()) {
      const Extraction r = OrbExtractor(p).extract(image);
      expectDefined(r, image, p);
      EXPECT_TRUE(r.keypoints.empty()) << "value " << value;
      double lo = 0.0, hi = 0.0;
      cv::minMaxLoc(r.image, &lo, &hi);
      EXPECT_EQ(lo, hi) << "a constant image stays constant";
      cv::minMaxLoc(r.cell_thresholds, &lo);
      EXPECT_GE(lo, p.orb.threshold_mode == ThresholdMode::kFixed ? 20 : p.threshold.c_min);
    }
  }
}

TEST(Degenerate, TinyImages) {
  // 1x1, smaller than the grid, smaller than the FAST circle, smaller than the edge border.
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(2, 3), cv::Size(4, 4), cv::Size(7, 7), cv::Size(38, 38),
                              cv::Size(39, 40), cv::Size(1, 500), cv::Size(500, 1)}) {
    cv::Mat image(size, CV_8UC1);
    cv::randu(image, 0, 256);
    for (const Params& p : allModes()) {
      const Extraction r = OrbExtractor(p).extract(image);
      expectDefined(r, image, p);
      if (size.width <= 2 * kEdgeThreshold || size.height <= 2 * kEdgeThreshold) {
        EXPECT_TRUE(r.keypoints.empty()) << size;
      }
    }
  }
}

TEST(Degenerate, ReusedOutputAcrossSizesAndAnEmptyFrame) {
  // One Extraction reused over frames of changing size, an empty one among them: each result is
  // that of a fresh call.
  cv::setNumThreads(2);
  Params p;
  p.orb.threads = 2;
  const OrbExtractor extractor(p);
  Extraction reused;
  cv::RNG rng(4);
  for (cv::Size size : {cv::Size(640, 480), cv::Size(0, 0), cv::Size(97, 61), cv::Size(640, 480), cv::Size(3, 2)}) {
    cv::Mat image(size, CV_8UC1);
    if (!image.empty()) {
      rng.fill(image, cv::RNG::UNIFORM, 0, 256);
      cv::GaussianBlur(image, image, cv::Size(3, 3), 0);
    }
    extractor.extract(image, reused);
    const Extraction fresh = extractor.extract(image);
    ASSERT_EQ(reused.keypoints.size(), fresh.keypoints.size()) << size;
    EXPECT_EQ(cv::norm(reused.descriptors, fresh.descriptors, cv::NORM_INF), 0.0) << size;
    EXPECT_EQ(reused.image.size(), size);
    EXPECT_EQ(reused.cell_thresholds.size(), cv::Size(p.threshold.grid_size, p.threshold.grid_size)) << size;
    EXPECT_EQ(reused.descriptors.rows, static_cast<int>(reused.keypoints.size())) << size;
  }
}

TEST(Degenerate, EmptyImage) {
  const Extraction r = OrbExtractor().extract(cv::Mat());
  EXPECT_TRUE(r.keypoints.empty());
  EXPECT_EQ(r.descriptors.rows, 0);
  EXPECT_TRUE(r.image.empty());
  EXPECT_EQ(r.cell_thresholds.size(), cv::Size(5, 5));  // the grid's thresholds, c_min each
}

TEST(Degenerate, NonContinuousRoiInput) {
  cv::Mat big(600, 900, CV_8UC1);
  cv::randu(big, 0, 256);
  const cv::Mat roi = big(cv::Rect(13, 7, 640, 480));
  const cv::Mat copy = roi.clone();
  const Extraction a = OrbExtractor().extract(roi);
  const Extraction b = OrbExtractor().extract(copy);
  ASSERT_EQ(a.keypoints.size(), b.keypoints.size());
  EXPECT_EQ(cv::norm(a.descriptors, b.descriptors, cv::NORM_HAMMING), 0.0);
}

TEST(Degenerate, TheExtractorKeepsNoReferenceToTheCallersImage) {
  // Without enhancement the extraction reads the caller's image directly; once its result is gone,
  // nothing of the extractor (its pooled workspaces) may hold on to that image.
  cv::Mat image(240, 320, CV_8UC1);
  cv::randu(image, 0, 256);
  for (int threads : {1, 2}) {
    Params p = Params::baseline();
    p.orb.threads = threads;
    const OrbExtractor extractor(p);
    {
      const Extraction r = extractor.extract(image);
      EXPECT_EQ(r.image.data, image.data);
    }
    EXPECT_EQ(image.u->refcount, 1) << threads << " thread(s)";
  }
}
