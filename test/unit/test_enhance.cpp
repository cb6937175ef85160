#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/enhance.h"
#include "test_images.h"

using namespace enhanced_orb;

namespace {

// ALGORITHM.md section 1 written out with OpenCV calls, independent of the library's single pass.
cv::Mat referenceEnhance(const cv::Mat& gray, const EnhanceParams& p, bool poor) {
  cv::Mat in_f, f, f_rounded;
  gray.convertTo(in_f, CV_32F);
  cv::GaussianBlur(in_f, f, cv::Size(p.blur_ksize, p.blur_ksize), p.blur_sigma, p.blur_sigma, cv::BORDER_REFLECT_101);
  cv::Mat e = in_f + p.sharpening * (in_f - f);  // eq 19
  if (poor) {
    f.convertTo(f_rounded, CV_8U);
    Histogram hist{};
    for (auto it = f_rounded.begin<uchar>(); it != f_rounded.end<uchar>(); ++it) {
      ++hist[*it];
    }
    const ToneLut lut = truncatedGammaLut(hist, p.alpha, p.tau);
    cv::Mat lut_mat(1, 256, CV_32F, const_cast<float*>(lut.data()));
    cv::Mat gamma_f;
    cv::LUT(f_rounded, lut_mat, gamma_f);
    e += p.beta * (gamma_f - f);  // eqs 17 and 20
  }
  cv::Mat out;
  e.convertTo(out, CV_8U);
  return out;
}

double maxAbsDiff(const cv::Mat& a, const cv::Mat& b) {
  return cv::norm(a, b, cv::NORM_INF);
}

cv::Mat darkScene() {
  cv::Mat dark;
  test::syntheticScene(cv::Size(160, 120)).convertTo(dark, CV_8U, 0.4);
  return dark;
}

}  // namespace

TEST(ToGray, Mono8IsNotCopied) {
  const cv::Mat image = test::syntheticScene(cv::Size(40, 30));
  EXPECT_EQ(toGray(image, PixelFormat::kMono8).data, image.data);
}

TEST(ToGray, Mono16IsScaledBy1Over257) {
  cv::Mat image(1, 4, CV_16UC1);
  image.at<uint16_t>(0) = 0;
  image.at<uint16_t>(1) = 257 * 10;
  image.at<uint16_t>(2) = 257 * 200;
  image.at<uint16_t>(3) = 65535;
  const cv::Mat gray = toGray(image, PixelFormat::kMono16);
  ASSERT_EQ(gray.type(), CV_8UC1);
  EXPECT_EQ(gray.at<uchar>(0), 0);
  EXPECT_EQ(gray.at<uchar>(1), 10);
  EXPECT_EQ(gray.at<uchar>(2), 200);
  EXPECT_EQ(gray.at<uchar>(3), 255);
}

TEST(ToGray, ChannelOrderIsRespected) {
  // Pure red: luma 0.299 * 255 = 76; pure blue: 0.114 * 255 = 29.
  const cv::Mat red_bgr(1, 1, CV_8UC3, cv::Scalar(0, 0, 255));
  EXPECT_EQ(toGray(red_bgr, PixelFormat::kBGR).at<uchar>(0), 76);
  EXPECT_EQ(toGray(red_bgr, PixelFormat::kRGB).at<uchar>(0), 29);
  const cv::Mat red_rgba(1, 1, CV_8UC4, cv::Scalar(255, 0, 0, 255));
  EXPECT_EQ(toGray(red_rgba, PixelFormat::kRGBA).at<uchar>(0), 76);
  EXPECT_EQ(toGray(red_rgba, PixelFormat::kBGRA).at<uchar>(0), 29);
}

TEST(ToGray, TypeMismatchThrows) {
  EXPECT_THROW(toGray(cv::Mat(2, 2, CV_8UC3), PixelFormat::kMono8), std::invalid_argument);
  EXPECT_THROW(toGray(cv::Mat(2, 2, CV_32FC1), PixelFormat::kMono16), std::invalid_argument);
  EXPECT_THROW(toGray(cv::Mat(2, 2, CV_8UC1), PixelFormat::kBGRA), std::invalid_argument);
}

TEST(Lambda, IsTheStandardDeviationOfTheScaledImage) {
  cv::Mat image(2, 2, CV_8UC1, cv::Scalar(0));
  image.row(0).setTo(255);
  EXPECT_NEAR(imageLambda(image), 0.5, 1e-12);  // eq 7: half 0, half 1
  EXPECT_DOUBLE_EQ(imageLambda(cv::Mat(3, 3, CV_8UC1, cv::Scalar(77))), 0.0);
  EXPECT_DOUBLE_EQ(imageLambda(cv::Mat()), 0.0);
}

TEST(Quality, ModesAndThePapersLiteralTest) {
  EnhanceParams p = Params::paper().enhance;
  EXPECT_TRUE(isPoorQuality(0.30, p));  // lambda > 0.25: "poor", as the paper states it
  EXPECT_FALSE(isPoorQuality(0.25, p));
  p.gamma_mode = GammaMode::kAlways;
  EXPECT_TRUE(isPoorQuality(0.0, p));
  p.gamma_mode = GammaMode::kNever;
  EXPECT_FALSE(isPoorQuality(0.5, p));
}

TEST(ToneLut, ThreeLevelHistogramByHand) {
  // n = 14: 1 at level 10, 4 at 20, 9 at 30. P_max = 9/14, P_min = 0. With alpha = 0.5 (eq 12)
  // P_w = 3/14, 6/14, 9/14; their sum 18/14, so C_w = 1/6 on [10, 20), 1/2 on [20, 30), 1 from 30.
  Histogram h{};
  h[10] = 1;
  h[20] = 4;
  h[30] = 9;
  const ToneLut lut = truncatedGammaLut(h, 0.5, 0.3);
  EXPECT_NEAR(lut[5], 5.0, 1e-4);  // C_w = 0 below level 10: gamma 1, the identity
  EXPECT_NEAR(lut[15], 255.0 * std::pow(15.0 / 255.0, 5.0 / 6.0), 1e-3);
  EXPECT_NEAR(lut[25], 255.0 * std::pow(25.0 / 255.0, 0.5), 1e-3);
  EXPECT_NEAR(lut[40], 255.0 * std::pow(40.0 / 255.0, 0.3), 1e-3);  // 1 - C_w = 0 truncated at tau
  EXPECT_NEAR(lut[255], 255.0, 1e-3);
}

TEST(ToneLut, FlatHistogramAndTruncationAtTau) {
  // P_max = P_min: every P_w = P_max (eq 12), so C_wi = (i + 1) / 256.
  Histogram h;
  h.fill(10);
  for (double tau : {0.3, 0.7}) {
    const ToneLut lut = truncatedGammaLut(h, 0.2, tau);
    for (int i : {1, 50, 100, 200, 254}) {
      const double gamma = std::max(tau, 1.0 - (i + 1) / 256.0);
      EXPECT_NEAR(lut[i], 255.0 * std::pow(i / 255.0, gamma), 1e-3) << "level " << i << ", tau " << tau;
    }
  }
}

TEST(ToneLut, TwoLevelHistogram) {
  // Half the pixels at 0, half at 255: C_w = 1/2 below 255, so gamma_i = max(tau, 1/2).
  Histogram h{};
  h[0] = 50;
  h[255] = 50;
  EXPECT_NEAR(truncatedGammaLut(h, 0.2, 0.3)[64], 255.0 * std::sqrt(64.0 / 255.0), 1e-3);
  EXPECT_NEAR(truncatedGammaLut(h, 0.2, 0.7)[64], 255.0 * std::pow(64.0 / 255.0, 0.7), 1e-3);
}

TEST(Enhance, NoSharpeningNoMaskIsTheIdentity) {
  EnhanceParams p = Params::paper().enhance;
  p.sharpening = 0.0;
  p.beta = 0.0;
  const cv::Mat dark = darkScene();
  cv::Mat bright;
  cv::bitwise_not(dark, bright);
  for (GammaMode mode : {GammaMode::kAlways, GammaMode::kNever}) {
    p.gamma_mode = mode;
    EXPECT_EQ(maxAbsDiff(enhance(dark, p).image, dark), 0.0);
    EXPECT_EQ(maxAbsDiff(enhance(bright, p).image, bright), 0.0);
  }
}

TEST(Enhance, GoodImageIsOnlySharpened) {
  // Not poor: E = I + sharpening (I - f) whatever beta is (eq 19).
  EnhanceParams p = Params::paper().enhance;
  p.gamma_mode = GammaMode::kNever;
  p.beta = 1.5;
  p.sharpening = 0.0;
  const cv::Mat image = darkScene();
  EXPECT_EQ(maxAbsDiff(enhance(image, p).image, image), 0.0);
  p.sharpening = 1.0;
  const EnhanceResult r = enhance(image, p);
  EXPECT_FALSE(r.poor_quality);
  EXPECT_LE(maxAbsDiff(r.image, referenceEnhance(image, p, false)), 1.0);
  EXPECT_GT(maxAbsDiff(r.image, image), 10.0);  // sharpening does something on edges
}

TEST(Enhance, PoorImageMatchesTheEquations) {
  EnhanceParams p = Params::paper().enhance;
  p.gamma_mode = GammaMode::kAlways;
  const cv::Mat image = darkScene();
  const EnhanceResult r = enhance(image, p);
  EXPECT_TRUE(r.poor_quality);
  EXPECT_FALSE(r.inverted);
  EXPECT_LE(maxAbsDiff(r.image, referenceEnhance(image, p, true)), 1.0);
  EXPECT_GT(cv::mean(r.image)[0], cv::mean(image)[0] + 5.0);  // the gamma brightens a dark image
}

TEST(Enhance, BrightPoorImageIsInvertedAndBack) {
  EnhanceParams p = Params::paper().enhance;
  p.gamma_mode = GammaMode::kAlways;
  const cv::Mat dark = darkScene();
  cv::Mat bright;
  cv::bitwise_not(dark, bright);
  ASSERT_GT(cv::mean(bright)[0], 128.0);
  const EnhanceResult r = enhance(bright, p);
  EXPECT_TRUE(r.inverted);
  cv::Mat expected;
  cv::bitwise_not(enhance(dark, p).image, expected);  // step 4: enhance the negative, negate back
  EXPECT_EQ(maxAbsDiff(r.image, expected), 0.0);
  EXPECT_LT(cv::mean(r.image)[0], cv::mean(bright)[0] - 5.0);  // darkens a bright image
}

TEST(Enhance, AutoModeFollowsLambda) {
  EnhanceParams p = Params::paper().enhance;
  const cv::Mat high_contrast = test::syntheticScene(cv::Size(160, 120));
  const cv::Mat low_contrast = darkScene() * 0.2;
  const EnhanceResult a = enhance(high_contrast, p);
  const EnhanceResult b = enhance(low_contrast, p);
  EXPECT_GT(a.lambda, p.std_threshold);
  EXPECT_TRUE(a.poor_quality);
  EXPECT_LT(b.lambda, p.std_threshold);
  EXPECT_FALSE(b.poor_quality);
}

TEST(Enhance, BadInput) {
  EXPECT_TRUE(enhance(cv::Mat(), EnhanceParams()).image.empty());
  EXPECT_THROW(enhance(cv::Mat(4, 4, CV_8UC3), EnhanceParams()), std::invalid_argument);
  EnhanceParams bad;
  bad.tau = 2.0;
  EXPECT_THROW(enhance(darkScene(), bad), std::invalid_argument);
}

TEST(ToneCurve, EqualizingLutIsMonotoneWithSlopeAtLeastTau) {
  WeightedHistogram h{};
  for (int i = 20; i < 60; ++i) {
    h[i] = 1.0 + (i % 7);
  }
  for (double tau : {0.0, 0.3, 1.0}) {
    const ToneLut lut = equalizingLut(h, 0.5, tau);
    EXPECT_NEAR(lut[255], 255.0f, 1e-3);
    for (int i = 0; i < 255; ++i) {
      EXPECT_GE(lut[i + 1] - lut[i], tau - 1e-4) << "tau " << tau << " level " << i;
    }
    if (tau == 1.0) {
      EXPECT_NEAR(lut[100], 100.0f, 1e-3);  // tau 1: the identity
    }
  }
  // The occupied levels are stretched: levels 20..60 span most of the range at tau 0.
  const ToneLut stretched = equalizingLut(h, 0.5, 0.0);
  EXPECT_LT(stretched[19], 5.0f);
  EXPECT_GT(stretched[59], 250.0f);
  const ToneLut empty = equalizingLut(WeightedHistogram{}, 0.5, 0.3);
  EXPECT_FLOAT_EQ(empty[77], 77.0f);
}

TEST(ToneCurve, StretchingLutMapsTheQuantilesToTheEnds) {
  Histogram h{};
  h[10] = 10;  // 10 % of 100 pixels at each end beyond the stretched range
  h[40] = 40;
  h[60] = 40;
  h[90] = 10;
  const ToneLut all = stretchingLut(h, 0.0);  // tau 0: the darkest and brightest level
  EXPECT_FLOAT_EQ(all[10], 0.0f);
  EXPECT_FLOAT_EQ(all[90], 255.0f);
  EXPECT_FLOAT_EQ(all[50], 127.5f);
  const ToneLut clipped = stretchingLut(h, 0.1);  // exactly 10 % at or below 10: clipped
  EXPECT_FLOAT_EQ(clipped[40], 0.0f);
  EXPECT_FLOAT_EQ(clipped[60], 255.0f);
  EXPECT_FLOAT_EQ(clipped[10], 0.0f);
  EXPECT_FLOAT_EQ(clipped[50], 127.5f);
  const ToneLut under = stretchingLut(h, 0.09);  // less than the end bins hold: kept
  EXPECT_FLOAT_EQ(under[10], 0.0f);
  EXPECT_FLOAT_EQ(under[90], 255.0f);
  // One level, or none: nothing to stretch, the identity.
  Histogram one{};
  one[77] = 5;
  for (const ToneLut& lut : {stretchingLut(one, 0.2), stretchingLut(Histogram{}, 0.2)}) {
    for (int i = 0; i < 256; ++i) {
      EXPECT_FLOAT_EQ(lut[i], static_cast<float>(i));
    }
  }
}

TEST(Enhance, StretchUndoesAGainAndKeepsTheToneOrder) {
  const cv::Mat scene = test::syntheticScene();
  cv::Mat dark;
  scene.convertTo(dark, CV_8U, 0.25);
  EnhanceParams p;
  p.tone_curve = ToneCurve::kStretch;
  p.tau = 0.05;
  const cv::Mat from_scene = enhance(scene, p).image;
  const cv::Mat from_dark = enhance(dark, p).image;
  // A quarter of the light, stretched back: the same image up to the quantisation of the dark copy
  // (4 levels of the scene per level of the copy, times the stretch).
  cv::Scalar mean_scene, mean_dark;
  mean_scene = cv::mean(from_scene);
  mean_dark = cv::mean(from_dark);
  EXPECT_NEAR(mean_dark[0], mean_scene[0], 6.0);
  cv::Mat diff;
  cv::absdiff(from_scene, from_dark, diff);
  EXPECT_LT(cv::mean(diff)[0], 6.0);
  // The order of the filtered tones is kept: brighter in f is never darker in E.
  cv::Mat f;
  cv::GaussianBlur(dark, f, cv::Size(p.blur_ksize, p.blur_ksize), p.blur_sigma, p.blur_sigma,
                   cv::BORDER_REFLECT_101 | cv::BORDER_ISOLATED);
  int out_of_order = 0;
  for (int y = 0; y < f.rows; ++y) {
    for (int x = 1; x < f.cols; ++x) {
      const int df = f.at<uchar>(y, x) - f.at<uchar>(y, x - 1);
      const int de = from_dark.at<uchar>(y, x) - from_dark.at<uchar>(y, x - 1);
      out_of_order += (df > 0 && de < 0) || (df < 0 && de > 0);
    }
  }
  EXPECT_EQ(out_of_order, 0);
  // tau is live: clipping less stretches less.
  p.tau = 0.0;
  cv::Scalar m1, s1, m2, s2;
  cv::meanStdDev(from_dark, m1, s1);
  cv::meanStdDev(enhance(dark, p).image, m2, s2);
  EXPECT_LT(s2[0], s1[0] - 1.0);
  // A constant image stays as it is.
  const cv::Mat flat(40, 50, CV_8U, cv::Scalar(33));
  EXPECT_EQ(cv::countNonZero(enhance(flat, p).image != flat), 0);
}

TEST(ToneCurve, EdgeWeightedHistogramIgnoresFlatRegions) {
  cv::Mat f(64, 64, CV_8U, cv::Scalar(200));  // flat, bright
  f(cv::Rect(0, 0, 32, 64)).setTo(cv::Scalar(30));
  const WeightedHistogram h = edgeWeightedHistogram(f);
  // Samples at even x of even rows: only x = 32 (left neighbour 30, right 200) sees the edge, and
  // adds round(64 sqrt(170)) to the bin of 200, once per even row.
  const double weight = std::round(64.0 * std::sqrt(170.0));
  EXPECT_EQ(h[200], 32 * weight);
  double total = 0.0;
  for (double w : h) {
    total += w;
  }
  EXPECT_EQ(total, h[200]);
  // Borders clamp: a 1 x 1 image and a constant one weigh nothing.
  for (const WeightedHistogram& none : {edgeWeightedHistogram(cv::Mat(1, 1, CV_8U, cv::Scalar(9))),
                                        edgeWeightedHistogram(cv::Mat(5, 7, CV_8U, cv::Scalar(9)))}) {
    for (double w : none) {
      EXPECT_EQ(w, 0.0);
    }
  }
}

// On noise of many sizes (one column, runs of 512 columns and their ends): each even pixel of each
// even row weighs round(64 sqrt(|dx| + |dy|)), its neighbours clamped to the image, into its bin.
TEST(ToneCurve, EdgeWeightedHistogramWeighsEverySampleByItsClampedGradient) {
  cv::RNG rng(3);
  for (const cv::Size size : {cv::Size(1, 1), cv::Size(1, 6), cv::Size(2, 3), cv::Size(5, 4), cv::Size(512, 3),
                              cv::Size(513, 4), cv::Size(1030, 5)}) {
    cv::Mat f(size, CV_8U);
    rng.fill(f, cv::RNG::UNIFORM, 0, 256);
    WeightedHistogram expected{};
    for (int y = 0; y < f.rows; y += 2) {
      for (int x = 0; x < f.cols; x += 2) {
        const auto at = [&](int yy, int xx) {
          return static_cast<int>(f.at<uchar>(std::clamp(yy, 0, f.rows - 1), std::clamp(xx, 0, f.cols - 1)));
        };
        const int g = std::abs(at(y, x + 1) - at(y, x - 1)) + std::abs(at(y + 1, x) - at(y - 1, x));
        expected[f.at<uchar>(y, x)] += std::round(64.0 * std::sqrt(static_cast<double>(g)));
      }
    }
    const WeightedHistogram h = edgeWeightedHistogram(f);
    for (int i = 0; i < 256; ++i) {
      ASSERT_EQ(h[i], expected[i]) << size << " bin " << i;
    }
  }
}

TEST(Enhance, DefaultModeEqualisesDarkAndBrightAlikeWithoutInversion) {
  const cv::Mat scene = test::syntheticScene();
  cv::Mat dark, bright;
  scene.convertTo(dark, CV_8U, 0.15);
  scene.convertTo(bright, CV_8U, 0.3, 170);
  const EnhanceParams p;
  const EnhanceResult d = enhance(dark, p);
  const EnhanceResult b = enhance(bright, p);
  EXPECT_FALSE(d.inverted);
  EXPECT_FALSE(b.inverted);
  EXPECT_TRUE(d.poor_quality);  // gamma_mode always: the curve runs on every frame
  cv::Scalar dm, ds, bm, bs;
  cv::meanStdDev(d.image, dm, ds);
  cv::meanStdDev(b.image, bm, bs);
  cv::Scalar im, is, jm, js;
  cv::meanStdDev(dark, im, is);
  cv::meanStdDev(bright, jm, js);
  EXPECT_GT(ds[0], 2.0 * is[0]);  // contrast stretched
  EXPECT_GT(bs[0], 2.0 * js[0]);
  EXPECT_LT(std::abs(dm[0] - 128.0), 0.5 * std::abs(im[0] - 128.0));  // both brought towards mid-gray
  EXPECT_LT(std::abs(bm[0] - 128.0), 0.5 * std::abs(jm[0] - 128.0));
}
