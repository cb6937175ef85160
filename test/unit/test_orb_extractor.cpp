#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <set>
#include <stdexcept>
#include <utility>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/adaptive_threshold.h"
#include "enhanced_orb/orb_extractor.h"
#include "test_images.h"

using namespace enhanced_orb;

namespace {

// Keypoints of `all` with the given octave, and the matching descriptor rows.
std::pair<std::vector<cv::KeyPoint>, cv::Mat> octaveSubset(const Extraction& r, int octave, int border) {
  std::vector<cv::KeyPoint> kps;
  cv::Mat desc;
  for (size_t i = 0; i < r.keypoints.size(); ++i) {
    const cv::KeyPoint& kp = r.keypoints[i];
    if (kp.octave == octave && kp.pt.x >= border && kp.pt.y >= border && kp.pt.x < r.image.cols - border &&
        kp.pt.y < r.image.rows - border) {
      kps.push_back(kp);
      desc.push_back(r.descriptors.row(static_cast<int>(i)));
    }
  }
  return {kps, desc};
}

double angleDifference(double a, double b) {
  const double d = std::fmod(std::abs(a - b), 360.0);
  return std::min(d, 360.0 - d);
}

bool nearCellBorder(const cv::Point2f& p, cv::Size size, int grid) {
  for (int k = 0; k <= grid; ++k) {
    const cv::Rect cell = gridCell(size, grid, std::min(k, grid - 1), std::min(k, grid - 1));
    const int ex = k < grid ? cell.x : cell.x + cell.width;
    const int ey = k < grid ? cell.y : cell.y + cell.height;
    if (std::abs(p.x - ex) <= 2 || std::abs(p.y - ey) <= 2) {
      return true;
    }
  }
  return false;
}

}  // namespace

TEST(Descriptors, BitIdenticalToOpenCvOrbAtOctaveZero) {
  const Extraction r = OrbExtractor().extract(test::syntheticScene());
  // cv::ORB drops keypoints within its edge threshold (31); compare the ones it keeps.
  auto [kps, ours] = octaveSubset(r, 0, 31);
  ASSERT_GT(kps.size(), 100u);
  std::vector<cv::KeyPoint> theirs_kps = kps;
  cv::Mat theirs;
  cv::ORB::create()->compute(r.image, theirs_kps, theirs);
  ASSERT_EQ(theirs_kps.size(), kps.size());
  for (size_t i = 0; i < kps.size(); ++i) {
    ASSERT_EQ(theirs_kps[i].pt, kps[i].pt);
    ASSERT_EQ(theirs_kps[i].angle, kps[i].angle);
  }
  EXPECT_EQ(cv::norm(ours, theirs, cv::NORM_HAMMING), 0.0);
}

TEST(Descriptors, BitIdenticalToOpenCvOrbAtHigherOctaves) {
  // Same pyramid as cv::ORB (scale 1.2, INTER_LINEAR_EXACT from the previous level), so even the
  // keypoints of higher octaves describe identically.
  const Extraction r = OrbExtractor().extract(test::syntheticScene());
  const cv::Ptr<cv::ORB> orb = cv::ORB::create(500, 1.2f, 8);
  for (int octave = 1; octave < 4; ++octave) {
    auto [kps, ours] = octaveSubset(r, octave, static_cast<int>(std::ceil(31 * std::pow(1.2, octave))));
    ASSERT_GT(kps.size(), 10u) << "octave " << octave;
    std::vector<cv::KeyPoint> theirs_kps = kps;
    cv::Mat theirs;
    orb->compute(r.image, theirs_kps, theirs);
    ASSERT_EQ(theirs_kps.size(), kps.size());
    EXPECT_EQ(cv::norm(ours, theirs, cv::NORM_HAMMING), 0.0) << "octave " << octave;
  }
}

TEST(Orientation, PointsTowardsTheBrighterSide) {
  cv::Mat ramp(61, 61, CV_8UC1);
  for (int y = 0; y < ramp.rows; ++y) {
    for (int x = 0; x < ramp.cols; ++x) {
      ramp.at<uchar>(y, x) = static_cast<uchar>(2 * x + 40);
    }
  }
  const std::vector<std::pair<cv::Mat, float>> cases = {{ramp, 0.0f},
                                                        {ramp.t(), 90.0f},
                                                        {[&] {
                                                           cv::Mat m;
                                                           cv::flip(ramp, m, 1);
                                                           return m;
                                                         }(),
                                                         180.0f}};
  for (const auto& [image, expected] : cases) {
    std::vector<cv::KeyPoint> kps = {cv::KeyPoint(30.0f, 30.0f, 31.0f)};
    computeOrientation(image, kps);
    EXPECT_LT(angleDifference(kps[0].angle, expected), 0.5) << "expected " << expected << ", got " << kps[0].angle;
  }
  std::vector<cv::KeyPoint> edge = {cv::KeyPoint(3.0f, 30.0f, 31.0f, 123.0f)};
  computeOrientation(ramp, edge);
  EXPECT_EQ(edge[0].angle, 0.0f);  // patch leaves the image
}

TEST(Orientation, AgreesWithOpenCvOrb) {
  const cv::Mat image = test::syntheticScene();
  std::vector<cv::KeyPoint> theirs;
  cv::ORB::create(500, 1.2f, 1)->detect(image, theirs);
  ASSERT_GT(theirs.size(), 100u);
  std::vector<cv::KeyPoint> ours = theirs;
  computeOrientation(image, ours);
  // Both take the intensity centroid over the same disc of radius 15.
  for (size_t i = 0; i < ours.size(); ++i) {
    EXPECT_EQ(ours[i].angle, theirs[i].angle) << "at " << ours[i].pt;
  }
}

TEST(Corners, PerCellFastMatchesWholeImageFastWithOneThreshold) {
  const cv::Mat image = test::syntheticScene();
  const cv::Mat thresholds(5, 5, CV_32S, cv::Scalar(20));
  const std::vector<cv::KeyPoint> ours = detectCorners(image, thresholds);
  std::vector<cv::KeyPoint> whole;
  cv::FAST(image, whole, 20, true, cv::FastFeatureDetector::TYPE_9_16);
  const cv::Rect interior(kEdgeThreshold, kEdgeThreshold, image.cols - 2 * kEdgeThreshold,
                          image.rows - 2 * kEdgeThreshold);
  auto key = [](const cv::KeyPoint& kp) { return std::make_pair(cvRound(kp.pt.x), cvRound(kp.pt.y)); };
  std::set<std::pair<int, int>> ours_set, whole_set;
  for (const auto& kp : ours) {
    EXPECT_TRUE(interior.contains(kp.pt));
    EXPECT_TRUE(ours_set.insert(key(kp)).second) << "corner found twice";
  }
  for (const auto& kp : whole) {
    if (interior.contains(kp.pt)) {
      whole_set.insert(key(kp));
    }
  }
  ASSERT_GT(whole_set.size(), 200u);
  // Away from cell borders (where non-maximum suppression sees only one side) they are the same.
  for (const auto& p : whole_set) {
    if (!nearCellBorder(cv::Point2f(p.first, p.second), image.size(), 5)) {
      EXPECT_TRUE(ours_set.count(p)) << "missing " << p.first << "," << p.second;
    }
  }
  for (const auto& p : ours_set) {
    if (!nearCellBorder(cv::Point2f(p.first, p.second), image.size(), 5)) {
      EXPECT_TRUE(whole_set.count(p)) << "extra " << p.first << "," << p.second;
    }
  }
}

TEST(Corners, EachCellUsesItsOwnThreshold) {
  // Contrast at most 128: a cell with threshold 150 can find nothing, cells with 10 find plenty.
  cv::Mat image;
  test::syntheticScene(cv::Size(300, 300), 120).convertTo(image, CV_8U, 0.5);
  cv::Mat thresholds(2, 2, CV_32S, cv::Scalar(10));
  thresholds.at<int>(0, 1) = 150;  // top-right cell
  const std::vector<cv::KeyPoint> corners = detectCorners(image, thresholds);
  int top_right = 0, elsewhere = 0;
  for (const auto& kp : corners) {
    (kp.pt.x >= 150 && kp.pt.y < 150 ? top_right : elsewhere)++;
  }
  EXPECT_EQ(top_right, 0);
  EXPECT_GT(elsewhere, 50);
  thresholds.setTo(10);
  int top_right_low = 0;
  for (const auto& kp : detectCorners(image, thresholds)) {
    top_right_low += kp.pt.x >= 150 && kp.pt.y < 150;
  }
  EXPECT_GT(top_right_low, 10);
}

TEST(Budget, LevelBudgetsAreGeometricAndSumToTheTotal) {
  const std::vector<int> b = levelBudgets(1000, 8, 1.2);
  ASSERT_EQ(b.size(), 8u);
  int sum = 0;
  for (int n : b) {
    sum += n;
  }
  EXPECT_EQ(sum, 1000);
  EXPECT_EQ(b[0], 217);  // 1000 (1 - 1/1.2) / (1 - 1.2^-8)
  for (int i = 1; i + 1 < 8; ++i) {
    EXPECT_NEAR(b[i], b[i - 1] / 1.2, 1.0);
  }
  EXPECT_EQ(levelBudgets(5, 1, 1.2), std::vector<int>{5});
}

TEST(Budget, SelectionIsSpreadAndKeepsTheBest) {
  // 500 strong keypoints crowd one corner; 100 weak ones are spread over the image.
  std::vector<cv::KeyPoint> kps;
  for (int i = 0; i < 500; ++i) {
    kps.emplace_back(cv::Point2f(static_cast<float>(i % 25), static_cast<float>(i / 25)), 7.0f, -1.0f, 100.0f + i);
  }
  for (int i = 0; i < 100; ++i) {
    // One per 45-pixel selection cell, none in the crowded corner's cell.
    kps.emplace_back(cv::Point2f(static_cast<float>(80 + (i % 10) * 60), static_cast<float>(20 + (i / 10) * 48)), 7.0f,
                     -1.0f, 1.0f);
  }
  const std::vector<cv::KeyPoint> kept = selectSpread(kps, 150, cv::Size(640, 480));
  ASSERT_EQ(kept.size(), 150u);
  const long spread = std::count_if(kept.begin(), kept.end(), [](const cv::KeyPoint& kp) { return kp.pt.x >= 80; });
  EXPECT_EQ(spread, 100);  // every spread keypoint has a cell of its own
  // The crowded corner still contributes its strongest keypoint.
  const auto best = std::max_element(
      kept.begin(), kept.end(), [](const cv::KeyPoint& a, const cv::KeyPoint& b) { return a.response < b.response; });
  EXPECT_EQ(best->response, 599.0f);
  EXPECT_EQ(selectSpread(kps, 1000, cv::Size(640, 480)).size(), kps.size());
  EXPECT_TRUE(selectSpread(kps, 0, cv::Size(640, 480)).empty());
}

TEST(Extractor, UnlimitedBudgetKeepsEveryCornerOfEveryLevel) {
  const cv::Mat image = test::syntheticScene();
  Params params = Params::paper();
  const Extraction r = OrbExtractor(params).extract(image);
  const std::vector<cv::Mat> pyramid = buildPyramid(r.image, 8, 1.2);
  ASSERT_EQ(r.level_thresholds.size(), pyramid.size());
  size_t total = 0;
  for (size_t level = 0; level < pyramid.size(); ++level) {
    total += detectCorners(pyramid[level], cellThresholds(pyramid[level], params.threshold)).size();
    EXPECT_EQ(cv::norm(r.level_thresholds[level], cellThresholds(pyramid[level], params.threshold), cv::NORM_INF), 0);
  }
  EXPECT_EQ(r.keypoints.size(), total);
}

TEST(Extractor, KeypointsAreInLevelZeroCoordinates) {
  const cv::Mat image = test::syntheticScene();
  const Extraction r = OrbExtractor().extract(image);
  ASSERT_EQ(r.descriptors.rows, static_cast<int>(r.keypoints.size()));
  ASSERT_EQ(r.descriptors.cols, kDescriptorBytes);
  ASSERT_EQ(r.descriptors.type(), CV_8U);
  std::set<int> octaves;
  for (const cv::KeyPoint& kp : r.keypoints) {
    const float scale = std::pow(1.2f, static_cast<float>(kp.octave));
    octaves.insert(kp.octave);
    EXPECT_NEAR(kp.size, 31.0f * scale, 1e-3);
    EXPECT_GE(kp.pt.x, kEdgeThreshold * scale - 1e-3);
    EXPECT_LT(kp.pt.x, image.cols - kEdgeThreshold * scale + 1);
    EXPECT_GE(kp.pt.y, kEdgeThreshold * scale - 1e-3);
    EXPECT_LT(kp.pt.y, image.rows - kEdgeThreshold * scale + 1);
    EXPECT_GE(kp.angle, 0.0f);
    EXPECT_LT(kp.angle, 360.0f);
    EXPECT_GT(kp.response, 0.0f);
  }
  EXPECT_GE(octaves.size(), 6u);
  EXPECT_EQ(*octaves.rbegin(), 7);
}

TEST(Extractor, BudgetOfOneThousand) {
  Params params;
  params.orb.max_features = 1000;
  const Extraction r = OrbExtractor(params).extract(test::syntheticScene(cv::Size(752, 480), 400));
  EXPECT_EQ(r.keypoints.size(), 1000u);
  EXPECT_EQ(r.descriptors.rows, 1000);
}

TEST(Extractor, BaselineUsesTheFixedThresholdOnTheRawImage) {
  const cv::Mat image = test::syntheticScene();
  const Extraction r = OrbExtractor(Params::baseline()).extract(image);
  EXPECT_EQ(r.image.data, image.data);
  for (const cv::Mat& t : r.level_thresholds) {
    EXPECT_EQ(cv::countNonZero(t != 20), 0);
  }
  const Extraction adaptive = OrbExtractor().extract(image);
  double lo = 0.0;
  cv::minMaxLoc(adaptive.cell_thresholds, &lo);
  EXPECT_GE(lo, 7.0);
  EXPECT_GT(cv::norm(adaptive.image, image, cv::NORM_INF), 0.0);  // enhanced
}

TEST(Extractor, InvalidParamsAndInputThrow) {
  Params p;
  p.threshold.c_min = -3;
  try {
    OrbExtractor extractor(p);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("c_min = -3"), std::string::npos) << e.what();
  }
  EXPECT_THROW(OrbExtractor().extract(cv::Mat(50, 50, CV_16UC1)), std::invalid_argument);
}

TEST(Extractor, DarkenedEurocFrameGivesMoreKeypointsThanBaseline) {
  const cv::Mat frame = test::eurocFrame();
  REQUIRE_SHARED_DATA(!frame.empty(), "EuRoC frames under " + test::eurocDir());
  cv::Mat dark;
  frame.convertTo(dark, CV_8U, 0.4);  // I * 0.4
  const size_t improved = OrbExtractor(Params::paper()).extract(dark).keypoints.size();
  const size_t baseline = OrbExtractor(Params::baseline()).extract(dark).keypoints.size();
  RecordProperty("improved", static_cast<int>(improved));
  RecordProperty("baseline", static_cast<int>(baseline));
  EXPECT_GT(improved, baseline) << "improved " << improved << ", baseline " << baseline;
}

TEST(Extractor, CandidateRatioOneKeepsTheStrongestOfEachLevel) {
  const cv::Mat image = test::syntheticScene(cv::Size(752, 480), 400);
  Params all = Params::paper();
  all.enhance_enabled = false;
  Params top = all;
  top.orb.max_features = 300;
  top.orb.candidate_ratio = 1.0;
  const Extraction every = OrbExtractor(all).extract(image);
  const Extraction kept = OrbExtractor(top).extract(image);
  const std::vector<int> budgets = levelBudgets(300, top.orb.n_levels, top.orb.scale_factor);
  std::vector<float> level0;
  for (const cv::KeyPoint& kp : every.keypoints) {
    if (kp.octave == 0) {
      level0.push_back(kp.response);
    }
  }
  ASSERT_GT(level0.size(), static_cast<size_t>(budgets[0]));
  std::sort(level0.rbegin(), level0.rend());
  int kept0 = 0;
  for (const cv::KeyPoint& kp : kept.keypoints) {
    if (kp.octave == 0) {
      ++kept0;
      EXPECT_GE(kp.response, level0[budgets[0] - 1]);
    }
  }
  EXPECT_EQ(kept0, budgets[0]);
  // Spread over all candidates (ratio 0) keeps weaker corners too.
  top.orb.candidate_ratio = 0.0;
  float weakest = 1e9f;
  for (const cv::KeyPoint& kp : OrbExtractor(top).extract(image).keypoints) {
    if (kp.octave == 0) {
      weakest = std::min(weakest, kp.response);
    }
  }
  EXPECT_LT(weakest, level0[budgets[0] - 1]);
}

TEST(Extractor, DefaultModeParametersEachChangeTheOutput) {
  cv::Mat frame = test::eurocFrame();
  if (frame.empty()) {
    frame = test::syntheticScene(cv::Size(752, 480), 400);
  }
  cv::Mat dark;
  frame.convertTo(dark, CV_8U, 0.3);
  const Extraction reference = OrbExtractor().extract(dark);
  auto differs = [&](const char* name, const char* value) {
    Params p;
    EXPECT_EQ(setParam(p, name, value), "");
    const Extraction r = OrbExtractor(p).extract(dark);
    const bool image_differs = cv::norm(r.image, reference.image, cv::NORM_INF) > 0;
    bool keypoints_differ = r.keypoints.size() != reference.keypoints.size();
    for (size_t i = 0; !keypoints_differ && i < r.keypoints.size(); ++i) {
      keypoints_differ = r.keypoints[i].pt != reference.keypoints[i].pt;
    }
    return image_differs || keypoints_differ;
  };
  EXPECT_TRUE(differs("alpha", "1.0"));
  EXPECT_TRUE(differs("tau", "0.8"));
  EXPECT_TRUE(differs("beta", "0.5"));
  EXPECT_TRUE(differs("sharpening", "0.5"));
  EXPECT_TRUE(differs("blur_ksize", "5"));
  EXPECT_TRUE(differs("c_min", "80"));  // at a budget: once fewer corners than the candidates pass it
  EXPECT_TRUE(differs("threshold_scale", "1.5"));
  EXPECT_TRUE(differs("candidate_ratio", "0"));
  EXPECT_TRUE(differs("noise_floor", "8"));
  // c_min lifts every threshold.
  Params high;
  high.threshold.c_min = 40;
  double lo = 0.0;
  cv::minMaxLoc(OrbExtractor(high).extract(dark).cell_thresholds, &lo);
  EXPECT_GE(lo, 40.0);
}

// noise_floor: the candidates are the corners above noise_floor x the frame's noise, and at least
// the budget's strongest. A floor no corner reaches leaves the budget's strongest (candidate_ratio
// 1); a floor every corner passes leaves all of them (candidate_ratio 0).
TEST(Budget, NoiseFloorChoosesTheCandidatesByTheFramesNoise) {
  cv::Mat noisy = test::syntheticScene(cv::Size(640, 480), 300);
  cv::Mat noise(noisy.size(), CV_16S);
  cv::randn(noise, 0, 8);
  noisy.convertTo(noisy, CV_16S);
  cv::Mat(noisy + noise).convertTo(noisy, CV_8U);
  auto run = [&](double ratio, double floor, double cap = 0.0) {
    Params p;
    p.threshold.threshold_scale = 0.3;
    p.orb.candidate_ratio = ratio;
    p.orb.noise_floor = floor;
    p.orb.floor_candidate_ratio = cap;
    return OrbExtractor(p).extract(noisy);
  };
  auto same = [](const Extraction& a, const Extraction& b) {
    if (a.keypoints.size() != b.keypoints.size()) {
      return false;
    }
    for (size_t i = 0; i < a.keypoints.size(); ++i) {
      if (a.keypoints[i].pt != b.keypoints[i].pt || a.keypoints[i].octave != b.keypoints[i].octave) {
        return false;
      }
    }
    return cv::norm(a.descriptors, b.descriptors, cv::NORM_HAMMING) == 0.0;
  };
  const Extraction off = run(1.5, 0.0);
  EXPECT_EQ(OrbExtractor().extract(noisy).noise, 0.0);  // the default mode does not measure it
  EXPECT_EQ(off.noise, 0.0);                            // not measured when not used
  const Extraction high = run(1.5, 50.0);
  EXPECT_GT(high.noise, 1.0);
  EXPECT_TRUE(same(high, run(1.0, 0.0)));
  EXPECT_FALSE(same(high, off));
  EXPECT_TRUE(same(run(1.5, 1e-6), run(0.0, 0.0)));
  // In between, more corners pass a lower floor: the selection changes with it.
  EXPECT_FALSE(same(run(0.0, 4.0), run(0.0, 12.0)));

  // floor_candidate_ratio caps the corners above the floor at that many times the budget, the
  // strongest: with a floor every corner passes, the candidate_ratio selection of the same ratio;
  // with one no corner reaches, the budget's strongest still (a cap below 1 keeps those).
  // (candidate_ratio, set here to 1.5, is not used with a floor.)
  auto capped = [&](double cap, double floor) { return run(1.5, floor, cap); };
  EXPECT_TRUE(same(capped(3.0, 1e-6), run(3.0, 0.0)));
  EXPECT_FALSE(same(capped(3.0, 1e-6), run(0.0, 0.0)));
  EXPECT_TRUE(same(capped(0.0, 1e-6), run(0.0, 0.0)));
  EXPECT_TRUE(same(capped(0.5, 50.0), run(1.0, 0.0)));
  EXPECT_TRUE(same(capped(3.0, 50.0), high));
}

// A moving camera's frames get the cap too: it qualifies whichever floor the frame's selection uses.
TEST(Budget, FloorCandidateRatioCapsTheMovingSelection) {
  const cv::Mat scene = test::syntheticScene(cv::Size(640, 480), 300);
  Params p;
  p.orb.camera_motion = MotionMode::kMoving;
  const Extraction all = OrbExtractor(p).extract(scene);
  p.orb.floor_candidate_ratio = 1.0;
  const Extraction strongest = OrbExtractor(p).extract(scene);
  ASSERT_EQ(all.keypoints.size(), strongest.keypoints.size());
  // Capped at the budget, each level keeps its strongest corners: their weakest response is at
  // least the uncapped selection's, and somewhere above it.
  auto weakest = [](const Extraction& e, int octave) {
    float least = std::numeric_limits<float>::max();
    for (const cv::KeyPoint& kp : e.keypoints) {
      if (kp.octave == octave) {
        least = std::min(least, kp.response);
      }
    }
    return least;
  };
  bool above = false;
  for (int octave = 0; octave < p.orb.n_levels; ++octave) {
    EXPECT_GE(weakest(strongest, octave), weakest(all, octave)) << octave;
    above = above || weakest(strongest, octave) > weakest(all, octave);
  }
  EXPECT_TRUE(above);
  p.orb.camera_motion = MotionMode::kStill;  // the still selection has no floor here: no change
  const Extraction still = OrbExtractor(p).extract(scene);
  p.orb.floor_candidate_ratio = 0.0;
  EXPECT_EQ(cv::norm(still.descriptors, OrbExtractor(p).extract(scene).descriptors, cv::NORM_HAMMING), 0.0);
}

// The contract of the buffer-reusing extract(): a result the caller keeps keeps its values, the
// next call into the same Extraction writes elsewhere; one it does not keep is reused in place.
TEST(Extractor, KeptResultsKeepTheirValuesAndUnsharedBuffersAreReused) {
  for (Params params : {Params(), Params::paper(), Params::baseline()}) {
    params.orb.max_features = 200;  // the same number of rows each time: same-size buffers
    const OrbExtractor extractor(params);
    Extraction out;
    extractor.extract(test::syntheticScene(cv::Size(320, 240), 60, 1), out);
    const Extraction kept = out;  // shares every buffer of `out`
    const cv::Mat descriptors = kept.descriptors.clone();
    const cv::Mat thresholds = kept.cell_thresholds.clone();
    const std::vector<cv::KeyPoint> keypoints = kept.keypoints;
    ASSERT_EQ(keypoints.size(), 200u);
    extractor.extract(test::syntheticScene(cv::Size(320, 240), 60, 2), out);
    ASSERT_EQ(out.descriptors.rows, 200);
    EXPECT_NE(out.descriptors.data, kept.descriptors.data);
    EXPECT_EQ(cv::norm(kept.descriptors, descriptors, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(kept.cell_thresholds, thresholds, cv::NORM_INF), 0.0);
    EXPECT_EQ(kept.keypoints.size(), keypoints.size());
    if (params.enhance_enabled) {
      EXPECT_NE(out.image.data, kept.image.data);
    }
    // Nothing shares `out` now: the next call writes into its buffers.
    const std::uint8_t* own = out.descriptors.data;
    const int rows = out.descriptors.rows;
    extractor.extract(test::syntheticScene(cv::Size(320, 240), 60, 2), out);
    EXPECT_EQ(out.descriptors.rows, rows);
    EXPECT_EQ(out.descriptors.data, own);
  }
}
