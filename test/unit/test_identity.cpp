// The extractor against the straightforward reference (reference_extractor.h), bit for bit: on the
// shared EuRoC frames, for every mode and budget, every instruction set this machine runs and one
// and two threads; and each SIMD kernel against its scalar reference.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "enhanced_orb/orb_extractor.h"
#include "enhanced_orb/simd.h"
#include "kernels/fast_score.h"
#include "kernels/suppression.h"
#include "reference_extractor.h"
#include "test_images.h"

using namespace enhanced_orb;

namespace {

// Every `stride`-th cam0 frame of the shared excerpt, sorted by name.
std::vector<cv::Mat> eurocFrames(size_t stride) {
  std::vector<std::string> names;
  const std::filesystem::path dir = test::eurocDir() + "/mav0/cam0/data";
  if (std::filesystem::is_directory(dir)) {
    for (const auto& entry : std::filesystem::directory_iterator(dir)) {
      if (entry.path().extension() == ".png") {
        names.push_back(entry.path().string());
      }
    }
  }
  std::sort(names.begin(), names.end());
  std::vector<cv::Mat> frames;
  for (size_t i = 0; i < names.size(); i += stride) {
    frames.push_back(cv::imread(names[i], cv::IMREAD_GRAYSCALE));
  }
  return frames;
}

// Restores the process-wide instruction set when a test ends.
struct SimdScope {
  SimdLevel saved = activeSimdLevel();
  ~SimdScope() { setSimdLevel(saved); }
};

void expectSameKeypoints(const std::vector<cv::KeyPoint>& ours, const std::vector<cv::KeyPoint>& theirs,
                         const std::string& what) {
  ASSERT_EQ(ours.size(), theirs.size()) << what;
  for (size_t i = 0; i < ours.size(); ++i) {
    const cv::KeyPoint& a = ours[i];
    const cv::KeyPoint& b = theirs[i];
    ASSERT_TRUE(a.pt == b.pt && a.response == b.response && a.angle == b.angle && a.octave == b.octave &&
                a.size == b.size)
        << what << ": keypoint " << i << " (" << a.pt << " " << a.response << " " << a.angle << " " << a.octave
        << ") vs (" << b.pt << " " << b.response << " " << b.angle << " " << b.octave << ")";
  }
}

void expectSameMat(const cv::Mat& a, const cv::Mat& b, const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  ASSERT_EQ(a.type(), b.type()) << what;
  ASSERT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0) << what;
}

void expectSameExtraction(const Extraction& ours, const Extraction& theirs, const std::string& what) {
  expectSameKeypoints(ours.keypoints, theirs.keypoints, what);
  expectSameMat(ours.descriptors, theirs.descriptors, what + ", descriptors");
  expectSameMat(ours.image, theirs.image, what + ", image");
  ASSERT_EQ(ours.level_thresholds.size(), theirs.level_thresholds.size()) << what;
  for (size_t l = 0; l < ours.level_thresholds.size(); ++l) {
    expectSameMat(ours.level_thresholds[l], theirs.level_thresholds[l],
                  what + ", thresholds of level " + std::to_string(l));
  }
}

struct Mode {
  const char* name;
  Params params;
};

std::vector<Mode> modes() {
  return {{"default", Params()}, {"paper", Params::paper()}, {"baseline", Params::baseline()}};
}

}  // namespace

TEST(Kernels, FastScoreOfEveryInstructionSetEqualsTheScalarReference) {
  cv::RNG rng(3);
  std::vector<cv::Mat> images = {test::syntheticScene(cv::Size(203, 97)), cv::Mat(64, 301, CV_8UC1),
                                 cv::Mat(40, 130, CV_8UC1, cv::Scalar(200))};
  rng.fill(images[1], cv::RNG::UNIFORM, 0, 256);
  for (const cv::Mat& frame : eurocFrames(47)) {
    images.push_back(frame);
  }
  for (const cv::Mat& image : images) {
    // One floor for the row, and floors that change from pixel to pixel (-1: random, 0..40).
    for (int floor : {0, 6, 19, 60, 255, -1}) {
      std::vector<std::uint8_t> floors(static_cast<size_t>(image.cols));
      for (std::uint8_t& f : floors) {
        f = static_cast<std::uint8_t>(floor >= 0 ? floor : rng.uniform(0, 41));
      }
      cv::Mat expected(image.size(), CV_8UC1, cv::Scalar(0));
      for (int y = 3; y < image.rows - 3; ++y) {
        kernels::fastScoreRowScalar(image.ptr(y) + 3, static_cast<std::ptrdiff_t>(image.step), image.cols - 6,
                                    expected.ptr(y) + 3, floors.data());
      }
      for (SimdLevel level : supportedSimdLevels()) {
        // Row lengths of every remainder modulo the widest vector, short rows on the scalar tail.
        for (int width : {image.cols - 6, image.cols - 7, 13, 1}) {
          cv::Mat got(image.size(), CV_8UC1, cv::Scalar(0));
          for (int y = 3; y < image.rows - 3; ++y) {
            kernels::fastScoreRow(level, image.ptr(y) + 3, static_cast<std::ptrdiff_t>(image.step), width,
                                  got.ptr(y) + 3, floors.data());
          }
          const cv::Rect written(3, 3, width, image.rows - 6);
          ASSERT_EQ(cv::norm(got(written), expected(written), cv::NORM_INF), 0.0)
              << toString(level) << ", floor " << floor << ", width " << width << ", image " << image.size();
        }
      }
    }
  }
}

TEST(Kernels, SuppressionRowsOfEveryInstructionSetEqualTheScalarReference) {
  cv::RNG rng(21);
  for (int width : {301, 64, 17, 5}) {
    // Cells of uneven widths, scores around their thresholds, rows padded with one zero each side.
    std::vector<int> starts = {0};
    while (starts.back() < width) {
      starts.push_back(std::min(width, starts.back() + rng.uniform(2, 90)));
    }
    const int cells = static_cast<int>(starts.size()) - 1;
    std::vector<std::uint8_t> thresholds(cells);
    for (auto& t : thresholds) {
      t = static_cast<std::uint8_t>(rng.uniform(0, 40));
    }
    std::vector<std::uint8_t> scores(width);
    for (auto& m : scores) {
      m = static_cast<std::uint8_t>(rng.uniform(0, 3) == 0 ? rng.uniform(0, 256) : rng.uniform(0, 45));
    }
    auto rows = [&](SimdLevel level, std::vector<std::uint8_t>& b, std::vector<std::uint8_t>& around,
                    std::vector<std::uint8_t>& keep) {
      b.assign(width + 2, 0);
      around.assign(width + 2, 0);
      keep.assign(width, 0);
      kernels::suppressionRow(level, scores.data(), starts.data(), thresholds.data(), cells, b.data() + 1,
                              around.data() + 1);
      // The same row above and below: the keep kernel on its own output.
      kernels::suppressionKeep(level, b.data() + 1, around.data() + 1, around.data() + 1, starts.data(), cells,
                               keep.data());
    };
    std::vector<std::uint8_t> b0, a0, k0, b1, a1, k1;
    rows(SimdLevel::kScalar, b0, a0, k0);
    for (SimdLevel level : supportedSimdLevels()) {
      rows(level, b1, a1, k1);
      EXPECT_EQ(b1, b0) << toString(level) << ", width " << width;
      EXPECT_EQ(a1, a0) << toString(level) << ", width " << width;
      EXPECT_EQ(k1, k0) << toString(level) << ", width " << width;
    }
  }
}

TEST(Kernels, PortableBuildsHaveNoWiderKernels) {
  const std::vector<SimdLevel> levels = supportedSimdLevels();
  ASSERT_GE(levels.size(), 2u);
  EXPECT_EQ(levels[0], SimdLevel::kScalar);
  EXPECT_EQ(levels[1], SimdLevel::kVector128);
#if !defined(ENHANCED_ORB_X86_KERNELS)
  EXPECT_EQ(levels.size(), 2u);
#endif
  SimdScope scope;
  EXPECT_EQ(setSimdLevel(SimdLevel::kScalar), SimdLevel::kScalar);
  EXPECT_EQ(activeSimdLevel(), SimdLevel::kScalar);
  EXPECT_EQ(setSimdLevel(SimdLevel::kAvx2), levels.back());
}

TEST(Kernels, FastScoreIsTheLeastThresholdAtWhichCvFastRejects) {
  // m > t exactly when cv::FAST (no suppression) finds the pixel at threshold t.
  const cv::Mat image = test::syntheticScene(cv::Size(160, 120), 60, 11);
  cv::Mat scores(image.size(), CV_8UC1, cv::Scalar(0));
  const std::vector<std::uint8_t> no_floor(static_cast<size_t>(image.cols), 0);
  for (int y = 3; y < image.rows - 3; ++y) {
    kernels::fastScoreRowScalar(image.ptr(y) + 3, static_cast<std::ptrdiff_t>(image.step), image.cols - 6,
                                scores.ptr(y) + 3, no_floor.data());
  }
  for (int t : {0, 1, 7, 20, 80}) {
    std::vector<cv::KeyPoint> found;
    cv::FAST(image, found, t, false, cv::FastFeatureDetector::TYPE_9_16);
    cv::Mat fast(image.size(), CV_8UC1, cv::Scalar(0));
    for (const cv::KeyPoint& kp : found) {
      fast.at<std::uint8_t>(cvRound(kp.pt.y), cvRound(kp.pt.x)) = 255;
    }
    cv::Mat ours = scores > t;
    ours(cv::Rect(0, 0, image.cols, 3)).setTo(0);  // cv::FAST tests no pixel within 3 of the border
    EXPECT_EQ(cv::countNonZero(ours != fast), 0) << "threshold " << t;
    EXPECT_GT(found.size(), 0u);
  }
}

TEST(Enhance, IdenticalToTheReferenceInEveryModeAndSetting) {
  std::vector<cv::Mat> images = eurocFrames(4);
  images.push_back(test::syntheticScene());
  std::vector<std::pair<std::string, EnhanceParams>> settings = {{"default", EnhanceParams()},
                                                                 {"paper", Params::paper().enhance}};
  EnhanceParams p = Params::paper().enhance;
  p.gamma_mode = GammaMode::kAlways;
  settings.emplace_back("paper, gamma always", p);
  for (auto [name, change] : std::vector<std::pair<std::string, void (*)(EnhanceParams&)>>{
           {"beta 0.5", [](EnhanceParams& e) { e.beta = 0.5; }},
           {"sharpening 1", [](EnhanceParams& e) { e.sharpening = 1.0; }},
           {"blur 5x5, alpha 1, tau 0.4",
            [](EnhanceParams& e) {
              e.blur_ksize = 5;
              e.alpha = 1.0;
              e.tau = 0.4;
            }},
           {"never", [](EnhanceParams& e) { e.gamma_mode = GammaMode::kNever; }}}) {
    EnhanceParams e;
    change(e);
    settings.emplace_back(name, e);
  }
  cv::setNumThreads(3);
  for (const auto& [name, params] : settings) {
    for (size_t i = 0; i < images.size(); ++i) {
      const cv::Mat expected = reference::enhance(images[i], params).image;
      for (int threads : {1, 2, 3}) {
        expectSameMat(enhance(images[i], params, cv::Mat(), threads).image, expected,
                      name + ", image " + std::to_string(i) + ", " + std::to_string(threads) + " threads");
      }
    }
  }
}

TEST(Corners, ScoreMapDetectorEqualsCvFastPerCell) {
  SimdScope scope;
  std::vector<cv::Mat> images = eurocFrames(10);
  images.push_back(test::syntheticScene());
  cv::RNG rng(5);
  CornerWorkspace ws;
  std::vector<cv::KeyPoint> ours;
  for (SimdLevel simd : supportedSimdLevels()) {
    setSimdLevel(simd);
    for (const cv::Mat& image : images) {
      for (const cv::Mat& level : buildPyramid(image, 8, 1.2)) {
        // Random thresholds per cell, the clamped extremes among them.
        cv::Mat thresholds(5, 5, CV_32S);
        rng.fill(thresholds, cv::RNG::UNIFORM, 1, 40);
        thresholds.at<int>(0, 0) = 0;
        thresholds.at<int>(4, 4) = 255;
        detectCorners(level, thresholds, ws, ours);
        expectSameKeypoints(ours, reference::detectCorners(level, thresholds),
                            std::string(toString(simd)) + ", level " + std::to_string(level.cols));
      }
    }
  }
}

TEST(Extractor, IdenticalToTheReferenceOnEveryEurocFrameInEveryModeAndBudget) {
  cv::setNumThreads(2);  // OpenCV's pool must have room for the second thread
  const std::vector<cv::Mat> frames = eurocFrames(1);
  if (frames.empty()) {
    GTEST_SKIP() << "EuRoC frames not found under " << test::eurocDir() << " (../shared absent): skipped";
  }
  for (const Mode& mode : modes()) {
    for (int budget : {0, 1000}) {
      Params params = mode.params;
      params.orb.max_features = budget;
      Params two_threads = params;
      two_threads.orb.threads = 2;
      const OrbExtractor extractor(params);
      const OrbExtractor parallel(two_threads);
      Extraction reused;  // the buffer-reusing call, frame after frame
      for (size_t i = 0; i < frames.size(); ++i) {
        const Extraction expected = reference::extract(frames[i], params);
        const std::string what =
            std::string(mode.name) + ", budget " + std::to_string(budget) + ", frame " + std::to_string(i);
        expectSameExtraction(extractor.extract(frames[i]), expected, what);
        parallel.extract(frames[i], reused);
        expectSameExtraction(reused, expected, what + ", 2 threads, reused buffers");
      }
    }
  }
}

TEST(Extractor, IdenticalToTheReferenceAtEveryInstructionSet) {
  SimdScope scope;
  cv::setNumThreads(2);
  const std::vector<cv::Mat> frames = eurocFrames(19);
  if (frames.empty()) {
    GTEST_SKIP() << "EuRoC frames not found under " << test::eurocDir() << " (../shared absent): skipped";
  }
  for (const Mode& mode : modes()) {
    for (int budget : {0, 1000}) {
      Params params = mode.params;
      params.orb.max_features = budget;
      std::vector<Extraction> expected;
      for (const cv::Mat& frame : frames) {
        expected.push_back(reference::extract(frame, params));
      }
      for (SimdLevel simd : supportedSimdLevels()) {
        setSimdLevel(simd);
        for (int threads : {1, 2}) {
          params.orb.threads = threads;
          const OrbExtractor extractor(params);
          for (size_t i = 0; i < frames.size(); ++i) {
            expectSameExtraction(extractor.extract(frames[i]), expected[i],
                                 std::string(mode.name) + ", budget " + std::to_string(budget) + ", " + toString(simd) +
                                     ", " + std::to_string(threads) + " threads");
          }
        }
      }
    }
  }
}
