// The frame noise estimate: white noise read back at its deviation, edges and texture not counted.
#include <gtest/gtest.h>
#include <opencv2/core.hpp>

#include "enhanced_orb/noise.h"
#include "test_images.h"

namespace eo = enhanced_orb;

namespace {

cv::Mat withNoise(const cv::Mat& image, double sigma, std::uint64_t seed) {
  cv::Mat noise(image.size(), CV_32F);
  cv::RNG(seed).fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  cv::Mat f;
  image.convertTo(f, CV_32F);
  cv::Mat out;
  cv::Mat(f + noise).convertTo(out, CV_8U);
  return out;
}

}  // namespace

TEST(Noise, ReadsWhiteNoiseAtItsDeviation) {
  const cv::Mat flat(480, 640, CV_8U, cv::Scalar(128));
  EXPECT_EQ(eo::estimateNoise(flat), 0.0);
  for (double sigma : {3.0, 6.0, 12.0}) {
    EXPECT_NEAR(eo::estimateNoise(withNoise(flat, sigma, 1)), sigma, 0.15 * sigma) << sigma;
  }
}

TEST(Noise, EdgesAndTextureDoNotCount) {
  const cv::Mat scene = eo::test::syntheticScene(cv::Size(640, 480), 150);
  const double clean = eo::estimateNoise(scene);
  EXPECT_LT(clean, 1.0);
  // The same scene with noise of deviation 6 reads about 6, not the edges' contrast.
  EXPECT_NEAR(eo::estimateNoise(withNoise(scene, 6.0, 2)), 6.0, 1.2);
}

TEST(Noise, TinyAndEmptyImagesHaveNone) {
  EXPECT_EQ(eo::estimateNoise(cv::Mat()), 0.0);
  EXPECT_EQ(eo::estimateNoise(cv::Mat(4, 100, CV_8U, cv::Scalar(9))), 0.0);
  cv::Mat tiny(5, 5, CV_8U);
  cv::randu(tiny, 0, 256);
  EXPECT_GE(eo::estimateNoise(tiny), 0.0);
  EXPECT_THROW(eo::estimateNoise(cv::Mat(10, 10, CV_32F)), cv::Exception);
}
