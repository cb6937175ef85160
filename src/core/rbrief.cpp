#include "enhanced_orb/rbrief.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <mutex>
#include <stdexcept>
#include <string>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/simd.h"
#include "kernels/pyramid_rows.h"
#include "kernels/rotated_offsets.h"

namespace enhanced_orb {
namespace {

constexpr int kProbeRadius = 17;  // the tests lie within 13 pixels; the smoothing reaches 3 more
constexpr int kProbeSize = 2 * kProbeRadius + 2 * 20;

cv::Ptr<cv::ORB> openCvDescriber() {
  return cv::ORB::create(500, 1.2f, 1, 19, 0, 2, cv::ORB::HARRIS_SCORE, 31);
}

// For one bit: the probe positions that set it, as a box and a sum.
struct ProbeSet {
  int count = 0;
  int min_x = 1000, max_x = -1000, min_y = 1000, max_y = -1000;
  long sum_x = 0, sum_y = 0;

  void add(int x, int y) {
    ++count;
    min_x = std::min(min_x, x);
    max_x = std::max(max_x, x);
    min_y = std::min(min_y, y);
    max_y = std::max(max_y, y);
    sum_x += x;
    sum_y += y;
  }
};

// One coordinate of a test's points. A bright probe sets the bit near point 2, a dark one near
// point 1; on the side away from the other point each set reaches exactly 3 pixels (the smoothing's
// radius) beyond its point, and is symmetric about it along an axis where both points agree.
void solveAxis(const ProbeSet& bright, const ProbeSet& dark, int bright_min, int bright_max, int dark_min, int dark_max,
               long bright_sum, long dark_sum, int& c1, int& c2) {
  // sign(c1 - c2) from the sets' centroids: dark_sum / dark.count vs bright_sum / bright.count.
  const long difference = dark_sum * bright.count - bright_sum * dark.count;
  if (difference > 0) {
    c2 = bright_min + 3;
    c1 = dark_max - 3;
  } else if (difference < 0) {
    c2 = bright_max - 3;
    c1 = dark_min + 3;
  } else {
    c2 = (bright_min + bright_max) / 2;
    c1 = (dark_min + dark_max) / 2;
  }
}

std::array<BriefTest, 256> probeTests() {
  cv::Ptr<cv::ORB> orb = openCvDescriber();
  const cv::Point centre(kProbeSize / 2, kProbeSize / 2);
  std::array<ProbeSet, 256> bright, dark;
  cv::Mat image(kProbeSize, kProbeSize, CV_8UC1);
  cv::Mat descriptor;
  for (int dy = -kProbeRadius; dy <= kProbeRadius; ++dy) {
    for (int dx = -kProbeRadius; dx <= kProbeRadius; ++dx) {
      for (int polarity = 0; polarity < 2; ++polarity) {
        image.setTo(polarity == 0 ? 0 : 255);
        image.at<std::uint8_t>(centre.y + dy, centre.x + dx) = polarity == 0 ? 255 : 0;
        std::vector<cv::KeyPoint> keypoint{cv::KeyPoint(cv::Point2f(centre), 31.0f, 0.0f)};
        orb->compute(image, keypoint, descriptor);
        if (keypoint.size() != 1) {
          throw std::runtime_error("rBRIEF: cv::ORB dropped the probe keypoint");
        }
        for (int bit = 0; bit < 256; ++bit) {
          if (descriptor.at<std::uint8_t>(0, bit / 8) & (1 << (bit % 8))) {
            (polarity == 0 ? bright : dark)[bit].add(dx, dy);
          }
        }
      }
    }
  }
  std::array<BriefTest, 256> tests{};
  for (int bit = 0; bit < 256; ++bit) {
    const ProbeSet& b = bright[bit];
    const ProbeSet& d = dark[bit];
    if (b.count == 0 || d.count == 0) {
      throw std::runtime_error("rBRIEF: test " + std::to_string(bit) + " of cv::ORB never fires");
    }
    BriefTest& t = tests[bit];
    solveAxis(b, d, b.min_x, b.max_x, d.min_x, d.max_x, b.sum_x, d.sum_x, t.x1, t.x2);
    solveAxis(b, d, b.min_y, b.max_y, d.min_y, d.max_y, b.sum_y, d.sum_y, t.y1, t.y2);
  }
  return tests;
}

// Whether the tests and the rounding give cv::ORB's descriptors on a textured image, at every angle.
void verify(RotationRounding rounding) {
  cv::Mat image(160, 160, CV_8UC1);
  cv::RNG rng(12345);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  std::vector<cv::KeyPoint> keypoints;
  for (int i = 0; i < 400; ++i) {
    keypoints.emplace_back(
        cv::Point2f(static_cast<float>(rng.uniform(40, 120)), static_cast<float>(rng.uniform(40, 120))), 31.0f,
        i < 8 ? 45.0f * i : rng.uniform(0.0f, 360.0f));
  }
  std::vector<cv::KeyPoint> theirs_kps = keypoints;
  cv::Mat theirs;
  openCvDescriber()->compute(image, theirs_kps, theirs);
  SmoothingBuffers buffers;
  cv::Mat smoothed;
  smoothForDescription(image, buffers, smoothed);
  cv::Mat ours(static_cast<int>(keypoints.size()), 32, CV_8UC1);
  describe(smoothed, keypoints, ours, 0, rounding);
  if (theirs_kps.size() != keypoints.size() || cv::norm(ours, theirs, cv::NORM_HAMMING) != 0) {
    throw std::runtime_error("rBRIEF: the tests read off cv::ORB do not reproduce its descriptors");
  }
}

const std::array<BriefTest, 256>* g_tests = nullptr;
RotationRounding g_rounding;

RotationRounding findRotationRounding();

}  // namespace

const std::array<BriefTest, 256>& orbTests() {
  static std::once_flag once;
  static std::array<BriefTest, 256> tests;
  std::call_once(once, [] {
    tests = probeTests();
    g_tests = &tests;
    g_rounding = findRotationRounding();
    verify(g_rounding);
  });
  return tests;
}

RotationRounding orbRotationRounding() {
  orbTests();
  return g_rounding;
}

namespace {

constexpr int kSmoothingRadius = 3;

// The taps of cv::ORB's smoothing, single precision (kernels/pyramid_rows.h).
const float* gaussianTaps() {
  static const cv::Mat taps = cv::getGaussianKernel(7, 2, CV_32F);
  return taps.ptr<float>();
}

void openCvSmoothing(const cv::Mat& bordered, cv::Size size, cv::Mat& smoothed) {
  // cv::ORB blurs each level as a view into its bordered pyramid, and OpenCV filters such a view
  // (reading the pixels around it) by another path than a whole image, which rounds differently.
  cv::GaussianBlur(bordered(cv::Rect(kSmoothingRadius, kSmoothingRadius, size.width, size.height)), smoothed,
                   cv::Size(7, 7), 2, 2, cv::BORDER_REFLECT_101);
}

// The smoothing by this project's kernels, reading the level itself: each row, reflected rows
// beyond the level's first and last, is copied with its reflect-101 border into one padded row
// (which stays in cache, unlike a bordered copy of the level) for the row pass into a ring of
// seven; output row y reads rows y - 3 .. y + 3.
void kernelSmoothing(const cv::Mat& image, SimdLevel level, SmoothingBuffers& buffers, cv::Mat& smoothed) {
  constexpr int r = kSmoothingRadius;
  const int width = image.cols;
  buffers.rows.resize(7 * static_cast<size_t>(width));
  buffers.bordered.create(1, width + 2 * r, CV_8UC1);
  smoothed.create(image.size(), CV_8UC1);
  std::uint8_t* padded = buffers.bordered.ptr<std::uint8_t>();
  int left[r], right[r];  // the columns the border repeats
  for (int i = 0; i < r; ++i) {
    left[i] = cv::borderInterpolate(i - r, width, cv::BORDER_REFLECT_101);
    right[i] = cv::borderInterpolate(width + i, width, cv::BORDER_REFLECT_101);
  }
  const float* k = gaussianTaps();
  for (int y = -r; y < image.rows + r; ++y) {
    const std::uint8_t* row = image.ptr<std::uint8_t>(cv::borderInterpolate(y, image.rows, cv::BORDER_REFLECT_101));
    std::memcpy(padded + r, row, static_cast<size_t>(width));
    for (int i = 0; i < r; ++i) {
      padded[i] = row[left[i]];
      padded[r + width + i] = row[right[i]];
    }
    kernels::gaussianRow(level, padded, width, k, buffers.rows.data() + ((y + r) % 7) * static_cast<size_t>(width));
    if (y + r >= 6) {
      const float* ring[7];
      for (int j = 0; j < 7; ++j) {
        ring[j] = buffers.rows.data() + ((y + r - 6 + j) % 7) * static_cast<size_t>(width);
      }
      kernels::gaussianColumn(level, ring, width, k, smoothed.ptr<std::uint8_t>(y - r));
    }
  }
}

// Whether the scalar kernels reproduce the installed OpenCV's smoothing, on noise (every rounding
// case) and on a smooth ramp: decided once.
bool kernelsMatchOpenCv() {
  static const bool match = [] {
    cv::Mat image(61, 83, CV_8UC1);
    cv::RNG rng(11);
    rng.fill(image, cv::RNG::UNIFORM, 0, 256);
    cv::Mat ramp(40, 97, CV_8UC1);
    for (int y = 0; y < ramp.rows; ++y) {
      for (int x = 0; x < ramp.cols; ++x) {
        ramp.at<std::uint8_t>(y, x) = cv::saturate_cast<std::uint8_t>(2 * x + y);
      }
    }
    for (const cv::Mat& probe : {image, ramp}) {
      cv::Mat bordered, theirs, ours;
      SmoothingBuffers buffers;
      cv::copyMakeBorder(probe, bordered, kSmoothingRadius, kSmoothingRadius, kSmoothingRadius, kSmoothingRadius,
                         cv::BORDER_REFLECT_101);
      openCvSmoothing(bordered, probe.size(), theirs);
      kernelSmoothing(probe, SimdLevel::kScalar, buffers, ours);
      if (cv::norm(theirs, ours, cv::NORM_INF) != 0) {
        return false;
      }
    }
    return true;
  }();
  return match;
}

}  // namespace

bool smoothsWithKernels(SimdLevel level) {
  return kernels::hasVectorGaussianKernels(level) && kernelsMatchOpenCv();
}

void smoothForDescription(const cv::Mat& level, SmoothingBuffers& buffers, cv::Mat& smoothed) {
  const SimdLevel simd = activeSimdLevel();
  if (smoothsWithKernels(simd)) {
    kernelSmoothing(level, simd, buffers, smoothed);
    return;
  }
  constexpr int r = kSmoothingRadius;
  cv::copyMakeBorder(level, buffers.bordered, r, r, r, r, cv::BORDER_REFLECT_101);
  openCvSmoothing(buffers.bordered, level.size(), smoothed);
}

namespace {

// The tests' points as two float arrays: point 2 t is test t's first, point 2 t + 1 its second.
struct TestPoints {
  std::array<float, 512> x, y;
};

const TestPoints& testPoints(const std::array<BriefTest, 256>& tests) {
  static const TestPoints points = [&tests] {
    TestPoints p;
    for (int t = 0; t < 256; ++t) {
      p.x[2 * t] = static_cast<float>(tests[t].x1);
      p.y[2 * t] = static_cast<float>(tests[t].y1);
      p.x[2 * t + 1] = static_cast<float>(tests[t].x2);
      p.y[2 * t + 1] = static_cast<float>(tests[t].y2);
    }
    return p;
  }();
  return points;
}

}  // namespace

bool operator==(const RotationRounding& l, const RotationRounding& r) {
  return l.x == r.x && l.y == r.y;
}

namespace {

// The angle's cosine and sine as cv::ORB computes them: single precision throughout.
inline void cosineAndSine(float degrees, float& a, float& b) {
  const float angle = degrees * static_cast<float>(CV_PI / 180.f);
  a = std::cos(angle);
  b = std::sin(angle);
}

// The five roundings a compiler may give the rotation (a sum has one product fused at most).
constexpr RotationRounding kRoundings[] = {{Fusion::kNone, Fusion::kNone},
                                           {Fusion::kFirst, Fusion::kFirst},
                                           {Fusion::kFirst, Fusion::kSecond},
                                           {Fusion::kSecond, Fusion::kFirst},
                                           {Fusion::kSecond, Fusion::kSecond}};

// Whether the five roundings put test point (x, y) on one pixel at this angle.
bool roundingsAgree(float x, float y, float a, float b) {
  constexpr int kStep = 1024;  // an offset then names the point's pixel
  int first = 0;
  kernels::rotatedOffsetsScalar(kRoundings[0])(&x, &y, 1, a, b, kStep, &first);
  for (const RotationRounding& rounding : kRoundings) {
    int offset = 0;
    kernels::rotatedOffsetsScalar(rounding)(&x, &y, 1, a, b, kStep, &offset);
    if (offset != first) {
      return false;
    }
  }
  return true;
}

// Keypoints (many positions per angle) at angles where the roundings disagree on some test point.
// Such angles are rare (a rotated coordinate within an ulp of a .5 tie), so they are solved for:
// x a - y b = r cos(t + p) with r = |(x, y)|, p = atan2(y, x), equals k + 1/2 at
// t = +-acos((k + 1/2) / r) - p (x b + y a likewise with p - pi/2); the 64 float angles in degrees
// around each solution are tried in turn.
std::vector<cv::KeyPoint> tieKeypoints(const TestPoints& points, cv::RNG& rng) {
  std::vector<cv::KeyPoint> keypoints;
  int angles = 0;
  for (int j = 0; j < 512 && angles < 64; j += 7) {
    const double r = std::hypot(points.x[j], points.y[j]);
    for (int coordinate = 0; coordinate < 2 && angles < 64; ++coordinate) {
      const double phase = std::atan2(points.y[j], points.x[j]) - coordinate * CV_PI / 2;
      for (double half = -std::floor(r - 0.5) - 0.5; half < r && angles < 64; half += 1.0) {
        for (int sign : {-1, 1}) {
          const double radians = sign * std::acos(half / r) - phase;
          float degrees = static_cast<float>(std::fmod(radians * 180.0 / CV_PI + 720.0, 360.0));
          for (int step = 0; step < 32; ++step) {
            degrees = std::nextafter(degrees, 0.f);
          }
          for (int step = 0; step < 64; ++step, degrees = std::nextafter(degrees, 360.f)) {
            float a, b;
            cosineAndSine(degrees, a, b);
            if (!roundingsAgree(points.x[j], points.y[j], a, b)) {
              ++angles;
              for (int k = 0; k < 16; ++k) {
                keypoints.emplace_back(
                    cv::Point2f(static_cast<float>(rng.uniform(20, 140)), static_cast<float>(rng.uniform(20, 140))),
                    31.0f, degrees);
              }
              break;
            }
          }
        }
      }
    }
  }
  return keypoints;
}

// The one of the five roundings whose descriptors equal cv::ORB's on keypoints at ties.
RotationRounding findRotationRounding() {
  const TestPoints& points = testPoints(*g_tests);
  cv::Mat image(160, 160, CV_8UC1);
  cv::RNG rng(54321);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  std::vector<cv::KeyPoint> keypoints = tieKeypoints(points, rng);
  cv::Mat theirs;
  std::vector<cv::KeyPoint> theirs_kps = keypoints;
  openCvDescriber()->compute(image, theirs_kps, theirs);
  if (theirs_kps.size() != keypoints.size()) {
    throw std::runtime_error("rBRIEF: cv::ORB dropped keypoints of the rounding check");
  }
  SmoothingBuffers buffers;
  cv::Mat smoothed;
  smoothForDescription(image, buffers, smoothed);
  cv::Mat ours(static_cast<int>(keypoints.size()), 32, CV_8UC1);
  for (const RotationRounding& candidate : kRoundings) {
    describe(smoothed, keypoints, ours, 0, candidate);
    if (cv::norm(ours, theirs, cv::NORM_HAMMING) == 0) {
      return candidate;
    }
  }
  throw std::runtime_error("rBRIEF: no rounding of the test points' rotation reproduces cv::ORB's descriptors");
}

}  // namespace

void describe(const cv::Mat& smoothed, const std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors,
              int first_row) {
  describe(smoothed, keypoints, descriptors, first_row, g_tests ? g_rounding : orbRotationRounding());
}

void describe(const cv::Mat& smoothed, const std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors, int first_row,
              RotationRounding rounding) {
  const std::array<BriefTest, 256>& tests = g_tests ? *g_tests : orbTests();
  const TestPoints& points = testPoints(tests);
  const kernels::RotatedOffsetsKernel offsets = kernels::rotatedOffsetsKernel(activeSimdLevel(), rounding);
  const int step = static_cast<int>(smoothed.step);
  alignas(64) int offset[512];
  for (size_t k = 0; k < keypoints.size(); ++k) {
    const cv::KeyPoint& kp = keypoints[k];
    float a, b;
    cosineAndSine(kp.angle, a, b);
    offsets(points.x.data(), points.y.data(), 512, a, b, step, offset);
    const std::uint8_t* centre = smoothed.ptr<std::uint8_t>(cvRound(kp.pt.y)) + cvRound(kp.pt.x);
    std::uint8_t* out = descriptors.ptr<std::uint8_t>(first_row + static_cast<int>(k));
    for (int byte = 0; byte < 32; ++byte) {
      int value = 0;
      for (int bit = 0; bit < 8; ++bit) {
        const int t = 8 * byte + bit;
        value |= (centre[offset[2 * t]] < centre[offset[2 * t + 1]]) << bit;
      }
      out[byte] = static_cast<std::uint8_t>(value);
    }
  }
}

}  // namespace enhanced_orb
