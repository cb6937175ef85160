// The extractor against the straightforward reference (reference_extractor.h), bit for bit: on the
// shared EuRoC frames, for every mode and budget, every instruction set this machine runs and one
// and two threads; and each SIMD kernel against its scalar reference.
#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/orb_extractor.h"
#include "enhanced_orb/rbrief.h"
#include "enhanced_orb/simd.h"
#include "kernels/fast_score.h"
#include "kernels/patch_moments.h"
#include "kernels/pyramid_rows.h"
#include "kernels/rotated_offsets.h"
#include "kernels/suppression.h"
#include "kernels/table_lookup.h"
#include "linear_resize.h"
#include "reference_extractor.h"
#include "test_images.h"

using namespace enhanced_orb;

namespace {

// Every `stride`-th cam0 frame of the shared excerpt, sorted by name.
std::vector<cv::Mat> eurocFrames(size_t stride) {
  return test::cam0Frames(test::eurocDir(), stride);
}

// Every frame, or every ENHANCED_ORB_IDENTITY_STRIDE-th where that is set (the aarch64 job runs under
// an emulator, where every frame in every mode takes about 25 minutes).
size_t identityStride() {
  const char* stride = std::getenv("ENHANCED_ORB_IDENTITY_STRIDE");
  return stride && std::atoi(stride) > 1 ? static_cast<size_t>(std::atoi(stride)) : 1;
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
  return {{"default", Params()},
          {"paper", Params::paper()},
          {"baseline", Params::baseline()},
          {"motion", Params::motion()},  // also what the default mode's frames judged moving get (test_camera_motion)
          {"stretch", Params::stretch()}};
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

TEST(Kernels, PyramidRowsOfEveryInstructionSetEqualTheScalarReference) {
  cv::RNG rng(8);
  for (int width : {1, 7, 8, 15, 16, 17, 64, 301, 627}) {
    // Random taps inside a source of 1.3 x the width (and 16 bytes of slack), in blocks where they fit.
    const int source_width = width + width / 3 + 18;
    std::vector<std::uint8_t> source(static_cast<size_t>(source_width));
    rng.fill(source, cv::RNG::UNIFORM, 0, 256);
    std::vector<int> index(static_cast<size_t>(width));
    std::vector<std::uint16_t> weight(static_cast<size_t>(width));
    for (int x = 0; x < width; ++x) {
      index[x] = x + x / 3;
      weight[x] = static_cast<std::uint16_t>(x % 5 == 0 ? (x % 2) * 256 : rng.uniform(0, 257));
    }
    std::vector<int> block_start;
    std::vector<std::uint8_t> block_shuffle;
    for (int x = 0; x + 8 <= width; x += 8) {
      block_start.push_back(index[x]);
      for (int k = 0; k < 16; ++k) {
        block_shuffle.push_back(static_cast<std::uint8_t>(index[x + k / 2] - index[x] + k % 2));
      }
    }
    const kernels::LinearTaps taps{index.data(),       weight.data(),        width,
                                   block_start.data(), block_shuffle.data(), static_cast<int>(block_start.size())};
    std::vector<std::uint16_t> a(static_cast<size_t>(width)), b(static_cast<size_t>(width));
    kernels::linearRowScalar(source.data(), taps, a.data());
    for (int x = 0; x < width; ++x) {
      b[x] = static_cast<std::uint16_t>(rng.uniform(0, 65281));
    }
    std::vector<std::uint8_t> column(static_cast<size_t>(width));
    kernels::linearColumnScalar(a.data(), b.data(), 77, width, column.data());
    // The Gaussian: seven row passes of random bytes (and 6 more pixels each) feeding a column.
    const cv::Mat taps7 = cv::getGaussianKernel(7, 2, CV_32F);
    const float* k = taps7.ptr<float>();
    std::vector<std::uint8_t> pixels(static_cast<size_t>(7 * (width + 6)));
    rng.fill(pixels, cv::RNG::UNIFORM, 0, 256);
    std::vector<float> rows(static_cast<size_t>(7 * width));
    const float* ring[7];
    for (int j = 0; j < 7; ++j) {
      kernels::gaussianRowScalar(pixels.data() + j * (width + 6), width, k, rows.data() + j * width);
      ring[j] = rows.data() + j * width;
    }
    std::vector<std::uint8_t> smoothed(static_cast<size_t>(width));
    kernels::gaussianColumnScalar(ring, width, k, smoothed.data());
    for (SimdLevel level : supportedSimdLevels()) {
      const std::string what = std::string(toString(level)) + ", width " + std::to_string(width);
      std::vector<std::uint16_t> got(static_cast<size_t>(width));
      kernels::linearRow(level, source.data(), taps, got.data());
      EXPECT_EQ(got, a) << what;
      std::vector<std::uint8_t> got8(static_cast<size_t>(width));
      kernels::linearColumn(level, a.data(), b.data(), 77, width, got8.data());
      EXPECT_EQ(got8, column) << what;
      std::vector<float> row(static_cast<size_t>(width));
      kernels::gaussianRow(level, pixels.data(), width, k, row.data());
      EXPECT_EQ(0, std::memcmp(row.data(), rows.data(), row.size() * sizeof(float))) << what;
      kernels::gaussianColumn(level, ring, width, k, got8.data());
      EXPECT_EQ(got8, smoothed) << what;
    }
  }
}

TEST(Pyramid, ResizeEqualsOpenCvAtEveryInstructionSet) {
  SimdScope scope;
  std::vector<std::pair<cv::Mat, cv::Size>> cases;
  for (const cv::Mat& frame : eurocFrames(23)) {
    cv::Mat level = frame;
    for (int l = 1; l < 8; ++l) {
      const cv::Size size(cvRound(frame.cols / std::pow(1.2, l)), cvRound(frame.rows / std::pow(1.2, l)));
      cases.emplace_back(level, size);
      cv::resize(level, level, size, 0, 0, cv::INTER_LINEAR_EXACT);
    }
  }
  // Noise at random sizes, up and down, the halving OpenCV computes by area, one-pixel sides.
  cv::RNG rng(12);
  for (int i = 0; i < 60; ++i) {
    cv::Mat noise(rng.uniform(1, 90), rng.uniform(1, 120), CV_8UC1);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
    cases.emplace_back(noise, cv::Size(rng.uniform(1, 2 * noise.cols + 2), rng.uniform(1, 2 * noise.rows + 2)));
    cases.emplace_back(noise, cv::Size((noise.cols + 1) / 2, (noise.rows + 1) / 2));
  }
  const cv::Mat view = cases.front().first(cv::Rect(5, 7, 300, 200));  // a view with its own step
  cases.emplace_back(view, cv::Size(250, 167));
  for (SimdLevel simd : supportedSimdLevels()) {
    setSimdLevel(simd);
    LinearResize resize;
    for (const auto& [source, size] : cases) {
      cv::Mat theirs, ours;
      cv::resize(source, theirs, size, 0, 0, cv::INTER_LINEAR_EXACT);
      resize(source, ours, size, simd);
      expectSameMat(ours, theirs,
                    std::string(toString(simd)) + ", " + std::to_string(source.cols) + "x" +
                        std::to_string(source.rows) + " to " + std::to_string(size.width) + "x" +
                        std::to_string(size.height));
    }
  }
}

TEST(Pyramid, SmoothingEqualsCvOrbsAtEveryInstructionSet) {
  SimdScope scope;
  std::vector<cv::Mat> levels;
  for (const cv::Mat& frame : eurocFrames(31)) {
    for (const cv::Mat& level : buildPyramid(frame, 8, 1.2)) {
      levels.push_back(level);
    }
  }
  cv::RNG rng(4);
  for (cv::Size size : {cv::Size(1, 1), cv::Size(2, 7), cv::Size(5, 9), cv::Size(6, 2), cv::Size(11, 4),
                        cv::Size(12, 13), cv::Size(13, 1), cv::Size(17, 3), cv::Size(33, 40), cv::Size(200, 61)}) {
    cv::Mat noise(size, CV_8UC1);
    rng.fill(noise, cv::RNG::UNIFORM, 0, 256);
    levels.push_back(noise);
  }
  for (SimdLevel simd : supportedSimdLevels()) {
    setSimdLevel(simd);
    RecordProperty(std::string("smoothing_") + toString(simd), smoothsWithKernels(simd) ? "kernels" : "opencv");
    SmoothingBuffers buffers;
    for (const cv::Mat& level : levels) {
      cv::Mat bordered, theirs, ours;
      cv::copyMakeBorder(level, bordered, 3, 3, 3, 3, cv::BORDER_REFLECT_101);
      cv::GaussianBlur(bordered(cv::Rect(3, 3, level.cols, level.rows)), theirs, cv::Size(7, 7), 2, 2,
                       cv::BORDER_REFLECT_101);
      smoothForDescription(level, buffers, ours);
      expectSameMat(ours, theirs,
                    std::string(toString(simd)) + ", " + std::to_string(level.cols) + "x" + std::to_string(level.rows));
    }
  }
}

// Keypoints whose angle makes some test point round differently with and without fused
// multiply-add (the roundings of rbrief.h), at many positions each: for each test point, the float
// angles (in degrees) nearest to those that rotate it onto a .5 tie in x.
std::vector<cv::KeyPoint> keypointsAtRoundingTies(cv::RNG& rng) {
  std::vector<cv::KeyPoint> keypoints;
  std::vector<float> angles;
  for (const BriefTest& t : orbTests()) {
    const float px = static_cast<float>(t.x1), py = static_cast<float>(t.y1);
    const double radius = std::sqrt(px * px + py * py);
    if (radius < 2 || angles.size() >= 40) {
      continue;
    }
    // px cos(u) - py sin(u) = radius cos(u + atan2(py, px)) = 1.5
    const double degrees = (std::acos(1.5 / radius) - std::atan2(py, px)) * 180.0 / CV_PI;
    float angle = static_cast<float>(degrees < 0 ? degrees + 360.0 : degrees) - 0.0005f;
    for (; angle < degrees + 0.0005; angle = std::nextafter(angle, 400.f)) {
      const float radians = angle * static_cast<float>(CV_PI / 180.f);
      const float a = std::cos(radians), b = std::sin(radians);
      if (cvRound(px * a - py * b) != cvRound(std::fma(px, a, -(py * b))) ||
          cvRound(px * a - py * b) != cvRound(std::fma(-py, b, px * a))) {
        angles.push_back(angle);
        break;
      }
    }
  }
  for (float angle : angles) {
    for (int i = 0; i < 15; ++i) {
      keypoints.emplace_back(cv::Point2f(rng.uniform(20.f, 180.f), rng.uniform(20.f, 130.f)), 31.f, angle);
    }
  }
  return keypoints;
}

// On x86-64 Debian's OpenCV rounds the rotation without fused multiply-add, on arm64 with it: either
// way the descriptors are cv::ORB's, where the test points lie at ties too; and there the roundings
// differ, so a wrong one would fail.
TEST(Descriptors, RotationRoundsAsTheInstalledCvOrbAtTies) {
  cv::RNG rng(7);
  cv::Mat image(150, 200, CV_8UC1);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  std::vector<cv::KeyPoint> keypoints = keypointsAtRoundingTies(rng);
  ASSERT_GE(keypoints.size(), 150u);
  cv::Mat theirs;
  std::vector<cv::KeyPoint> kept = keypoints;
  cv::ORB::create(500, 1.2f, 1, 19, 0, 2, cv::ORB::HARRIS_SCORE, 31)->compute(image, kept, theirs);
  ASSERT_EQ(kept.size(), keypoints.size());
  SmoothingBuffers buffers;
  cv::Mat smoothed;
  smoothForDescription(image, buffers, smoothed);
  cv::Mat ours(static_cast<int>(keypoints.size()), 32, CV_8UC1);
  describe(smoothed, keypoints, ours, 0);
  RecordProperty("rotation_rounding_x", static_cast<int>(orbRotationRounding().x));
  RecordProperty("rotation_rounding_y", static_cast<int>(orbRotationRounding().y));
  EXPECT_EQ(cv::norm(ours, theirs, cv::NORM_HAMMING), 0.0)
      << "rounding found: x " << static_cast<int>(orbRotationRounding().x) << ", y "
      << static_cast<int>(orbRotationRounding().y);
  int others_differ = 0;
  for (Fusion x : {Fusion::kNone, Fusion::kFirst, Fusion::kSecond}) {
    for (Fusion y : {Fusion::kNone, Fusion::kFirst, Fusion::kSecond}) {
      const RotationRounding other{x, y};
      if (other == orbRotationRounding()) {
        continue;
      }
      cv::Mat theirs_other(ours.size(), CV_8UC1);
      describe(smoothed, keypoints, theirs_other, 0, other);
      others_differ += cv::norm(theirs_other, theirs, cv::NORM_HAMMING) > 0 ? 1 : 0;
    }
  }
  EXPECT_EQ(others_differ, 8) << "some other rounding gives the same descriptors on these keypoints";
}

// Every rounding of the rotation (rbrief.h) at every instruction set gives the scalar kernel's
// offsets: on points of the pattern's range, with cosine and sine chosen to put one point's rotated
// x or y within a few ulps of a .5 tie, where the roundings differ (so a kernel rounding otherwise
// would fail), and on array lengths that leave a tail shorter than a vector.
TEST(Kernels, RotatedOffsetsOfEveryInstructionSetEqualTheScalarReference) {
  constexpr int kPoints = 512, kStep = 777;
  cv::RNG rng(17);
  std::vector<float> x(kPoints), y(kPoints);
  for (int j = 0; j < kPoints; ++j) {
    x[j] = static_cast<float>(rng.uniform(-13, 14));
    y[j] = static_cast<float>(rng.uniform(-13, 14));
  }
  std::vector<int> expected(kPoints), got(kPoints), unfused(kPoints);
  int differ = 0;  // cases where some fused rounding moves a point from where kNone puts it
  for (int trial = 0; trial < 4000; ++trial) {
    const int j = trial % kPoints;
    const float tie = static_cast<float>(rng.uniform(-9, 9)) + 0.5f;
    float a = rng.uniform(-1.f, 1.f), b = rng.uniform(-1.f, 1.f);
    if (trial % 2 == 0 && y[j] != 0) {
      b = (x[j] * a - tie) / y[j];  // x a - y b near the tie
    } else if (y[j] != 0) {
      a = (tie - x[j] * b) / y[j];  // x b + y a near the tie
    }
    kernels::rotatedOffsetsScalar(RotationRounding{})(x.data(), y.data(), kPoints, a, b, kStep, unfused.data());
    for (Fusion fx : {Fusion::kNone, Fusion::kFirst, Fusion::kSecond}) {
      for (Fusion fy : {Fusion::kNone, Fusion::kFirst, Fusion::kSecond}) {
        const RotationRounding rounding{fx, fy};
        kernels::rotatedOffsetsScalar(rounding)(x.data(), y.data(), kPoints, a, b, kStep, expected.data());
        differ += expected != unfused ? 1 : 0;
        for (SimdLevel level : supportedSimdLevels()) {
          for (int n : {kPoints, 13, 7}) {
            std::fill(got.begin(), got.end(), -1);
            kernels::rotatedOffsetsKernel(level, rounding)(x.data(), y.data(), n, a, b, kStep, got.data());
            ASSERT_TRUE(std::equal(got.begin(), got.begin() + n, expected.begin()))
                << toString(level) << ", rounding " << static_cast<int>(fx) << static_cast<int>(fy) << ", n " << n
                << ", a " << a << ", b " << b;
            if (n < kPoints) {
              ASSERT_EQ(got[n], -1) << toString(level) << ": written past n = " << n;
            }
          }
        }
      }
    }
  }
  RecordProperty("rounding_cases_that_differ", differ);
  EXPECT_GT(differ, 400) << "the cases hardly put any point at a tie";
}

// The tone curve's table lookup of every instruction set equals cv::LUT: random tables (every entry
// of each 16-entry slice read), rows of every pixel value, of every length modulo the vector, and
// 1 pixel.
TEST(Kernels, TableLookupOfEveryInstructionSetEqualsCvLut) {
  cv::RNG rng(5);
  cv::Mat pixels(1, 256 * 3 + 45, CV_8UC1);
  for (int x = 0; x < pixels.cols; ++x) {
    pixels.at<std::uint8_t>(0, x) = static_cast<std::uint8_t>(x < 256 ? x : rng.uniform(0, 256));
  }
  for (int trial = 0; trial < 20; ++trial) {
    cv::Mat table(1, 256, CV_8UC1);
    rng.fill(table, cv::RNG::UNIFORM, 0, 256);
    if (trial == 0) {
      table.setTo(255);  // every entry's high bit set
    }
    cv::Mat expected;
    cv::LUT(pixels, table, expected);
    for (SimdLevel level : supportedSimdLevels()) {
      for (int n : {pixels.cols, pixels.cols - 1, 33, 32, 31, 1}) {
        cv::Mat got(pixels.size(), CV_8UC1, cv::Scalar(7));
        kernels::tableLookupKernel(level)(pixels.ptr(), n, table.ptr(), got.ptr());
        ASSERT_EQ(cv::norm(got.colRange(0, n), expected.colRange(0, n), cv::NORM_INF), 0.0)
            << toString(level) << ", n " << n << ", trial " << trial;
        if (n < pixels.cols) {
          ASSERT_EQ(got.at<std::uint8_t>(0, n), 7) << toString(level) << ": written past n = " << n;
        }
      }
    }
  }
}

// The patch moments of every instruction set equal the scalar reference's: on random pixels and
// weights, and at the extremes (every pixel 255, every weight 15 or -15), where a 16-bit pairwise
// sum would overflow if the products were wider.
TEST(Kernels, PatchMomentsOfEveryInstructionSetEqualTheScalarReference) {
  constexpr int kWeights = kernels::kMomentRows * kernels::kMomentColumns;
  cv::RNG rng(29);
  cv::Mat image(kernels::kMomentRows + 4, 50, CV_8UC1);
  std::vector<std::int8_t> u(kWeights), v(kWeights);
  for (int trial = 0; trial < 300; ++trial) {
    rng.fill(image, cv::RNG::UNIFORM, 0, 256);
    for (int i = 0; i < kWeights; ++i) {
      u[i] = static_cast<std::int8_t>(rng.uniform(-15, 16));
      v[i] = static_cast<std::int8_t>(rng.uniform(-15, 16));
    }
    if (trial < 2) {
      image.setTo(255);
      std::fill(u.begin(), u.end(), static_cast<std::int8_t>(trial == 0 ? 15 : -15));
      std::fill(v.begin(), v.end(), static_cast<std::int8_t>(trial == 0 ? -15 : 15));
    }
    const std::uint8_t* corner = image.ptr(rng.uniform(0, 4)) + rng.uniform(0, 18);
    std::int32_t m10 = 0, m01 = 0;
    kernels::patchMomentsScalar(corner, static_cast<std::ptrdiff_t>(image.step), u.data(), v.data(), &m10, &m01);
    if (trial < 2) {
      ASSERT_EQ(m10, (trial == 0 ? 15 : -15) * 255 * kWeights);
    }
    for (SimdLevel level : supportedSimdLevels()) {
      std::int32_t got10 = 0, got01 = 0;
      kernels::patchMomentsKernel(level)(corner, static_cast<std::ptrdiff_t>(image.step), u.data(), v.data(), &got10,
                                         &got01);
      ASSERT_EQ(got10, m10) << toString(level) << ", trial " << trial;
      ASSERT_EQ(got01, m01) << toString(level) << ", trial " << trial;
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
#if defined(ENHANCED_ORB_NEON_KERNELS)
  // On aarch64 the 16-byte level is NEON, with the pyramid's kernels (smoothing included).
  EXPECT_STREQ(toString(SimdLevel::kVector128), "neon");
  EXPECT_TRUE(kernels::hasVectorLinearKernels(SimdLevel::kVector128));
  EXPECT_TRUE(kernels::hasVectorGaussianKernels(SimdLevel::kVector128));
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
        EnhanceParams threaded = params;
        threaded.threads = threads;
        expectSameMat(enhance(images[i], threaded).image, expected,
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
  const std::vector<cv::Mat> frames = eurocFrames(identityStride());
  REQUIRE_SHARED_DATA(!frames.empty(), "EuRoC frames under " + test::eurocDir());
  for (const Mode& mode : modes()) {
    for (int budget : {0, 1000}) {
      Params params = mode.params;
      params.orb.max_features = budget;
      Params two_threads = params;
      two_threads.orb.threads = 2;
      two_threads.enhance.threads = 2;
      const OrbExtractor extractor(params);
      const OrbExtractor parallel(two_threads);
      Extraction reused;  // the buffer-reusing call, frame after frame
      for (size_t i = 0; i < frames.size(); ++i) {
        // A single image's parameters: the moving camera's selection for `motion`, else the still one.
        const Extraction expected = reference::extract(frames[i], params.forFrame(false));
        const std::string what =
            std::string(mode.name) + ", budget " + std::to_string(budget) + ", frame " + std::to_string(i);
        expectSameExtraction(extractor.extract(frames[i]), expected, what);
        parallel.extract(frames[i], reused);
        expectSameExtraction(reused, expected, what + ", 2 threads, reused buffers");
      }
    }
  }
}

// The moving selection finds each level's corners at the noise floor and searches a level again
// at its own thresholds when fewer than its share stand above it: on dark, noisy frames (where
// levels fall back), on clean ones (where none does), at small and large budgets and with a mask,
// it gives what the reference gives from every corner; with a mask, only corners the mask allows.
TEST(Extractor, CornersFoundAtTheNoiseFloorAreTheReferences) {
  const std::vector<cv::Mat> frames = eurocFrames(31);
  REQUIRE_SHARED_DATA(!frames.empty(), "EuRoC frames under " + test::eurocDir());
  cv::RNG rng(11);
  std::vector<cv::Mat> images;
  for (const cv::Mat& frame : frames) {
    images.push_back(frame);
    cv::Mat dark;
    frame.convertTo(dark, CV_32F, 0.08 * 4.0);  // x0.08 light, gain 4
    cv::Mat noise(frame.size(), CV_32F);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, 6.0);
    dark += noise;
    dark.convertTo(dark, CV_8U);
    images.push_back(dark);
  }
  cv::Mat mask(frames.front().size(), CV_8UC1, cv::Scalar(255));
  mask(cv::Rect(0, 0, mask.cols / 2, mask.rows / 3)).setTo(0);
  for (int budget : {150, 1000, 4000}) {
    for (double floor : {4.0, 8.0, 30.0}) {
      Params params = Params::motion();
      params.orb.max_features = budget;
      params.orb.moving_noise_floor = floor;
      const OrbExtractor extractor(params);
      const Params frame_params = params.forFrame(false);
      for (size_t i = 0; i < images.size(); ++i) {
        const std::string what =
            "budget " + std::to_string(budget) + ", floor " + std::to_string(floor) + ", image " + std::to_string(i);
        expectSameExtraction(extractor.extract(images[i]), reference::extract(images[i], frame_params), what);
        ExtractOptions masked;
        masked.mask = mask;
        Extraction ours;
        extractor.extract(images[i], masked, ours);
        ASSERT_FALSE(ours.keypoints.empty()) << what;
        for (const cv::KeyPoint& kp : ours.keypoints) {
          ASSERT_NE(mask.at<std::uint8_t>(std::min(cvRound(kp.pt.y), mask.rows - 1),
                                          std::min(cvRound(kp.pt.x), mask.cols - 1)),
                    0)
              << what;
        }
      }
    }
  }
}

TEST(Extractor, IdenticalToTheReferenceAtEveryInstructionSet) {
  SimdScope scope;
  cv::setNumThreads(2);
  const std::vector<cv::Mat> frames = eurocFrames(19);
  REQUIRE_SHARED_DATA(!frames.empty(), "EuRoC frames under " + test::eurocDir());
  for (const Mode& mode : modes()) {
    for (int budget : {0, 1000}) {
      Params params = mode.params;
      params.orb.max_features = budget;
      std::vector<Extraction> expected;
      for (const cv::Mat& frame : frames) {
        expected.push_back(reference::extract(frame, params.forFrame(false)));
      }
      for (SimdLevel simd : supportedSimdLevels()) {
        setSimdLevel(simd);
        for (int threads : {1, 2}) {
          params.orb.threads = threads;
          params.enhance.threads = threads;
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
