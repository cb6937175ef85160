#include "enhanced_orb/rbrief.h"

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

#include <opencv2/features2d.hpp>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/simd.h"
#include "kernels/pyramid_rows.h"

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

// Whether `tests` give cv::ORB's descriptors on a textured image, at every angle.
void verify() {
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
  describe(smoothed, keypoints, ours, 0);
  if (theirs_kps.size() != keypoints.size() || cv::norm(ours, theirs, cv::NORM_HAMMING) != 0) {
    throw std::runtime_error("rBRIEF: the tests read off cv::ORB do not reproduce its descriptors");
  }
}

const std::array<BriefTest, 256>* g_tests = nullptr;

}  // namespace

const std::array<BriefTest, 256>& orbTests() {
  static std::once_flag once;
  static std::array<BriefTest, 256> tests;
  std::call_once(once, [] {
    tests = probeTests();
    g_tests = &tests;
    verify();
  });
  return tests;
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

void kernelSmoothing(const cv::Mat& bordered, cv::Size size, SimdLevel level, std::vector<float>& rows,
                     cv::Mat& smoothed) {
  const size_t width = static_cast<size_t>(size.width);
  rows.resize(7 * width);
  smoothed.create(size, CV_8UC1);
  const float* k = gaussianTaps();
  // Row passes into a ring of seven: output row y reads bordered rows y .. y + 6.
  for (int y = 0; y < bordered.rows; ++y) {
    kernels::gaussianRow(level, bordered.ptr<std::uint8_t>(y), size.width, k, rows.data() + (y % 7) * width);
    if (y >= 6) {
      const float* ring[7];
      for (int j = 0; j < 7; ++j) {
        ring[j] = rows.data() + ((y - 6 + j) % 7) * width;
      }
      kernels::gaussianColumn(level, ring, size.width, k, smoothed.ptr<std::uint8_t>(y - 6));
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
      std::vector<float> rows;
      cv::copyMakeBorder(probe, bordered, kSmoothingRadius, kSmoothingRadius, kSmoothingRadius, kSmoothingRadius,
                         cv::BORDER_REFLECT_101);
      openCvSmoothing(bordered, probe.size(), theirs);
      kernelSmoothing(bordered, probe.size(), SimdLevel::kScalar, rows, ours);
      if (cv::norm(theirs, ours, cv::NORM_INF) != 0) {
        return false;
      }
    }
    return true;
  }();
  return match;
}

}  // namespace

void smoothForDescription(const cv::Mat& level, SmoothingBuffers& buffers, cv::Mat& smoothed) {
  constexpr int r = kSmoothingRadius;
  cv::copyMakeBorder(level, buffers.bordered, r, r, r, r, cv::BORDER_REFLECT_101);
  const SimdLevel simd = activeSimdLevel();
  if (simd >= SimdLevel::kAvx2 && kernelsMatchOpenCv()) {
    kernelSmoothing(buffers.bordered, level.size(), simd, buffers.rows, smoothed);
  } else {
    openCvSmoothing(buffers.bordered, level.size(), smoothed);
  }
}

namespace {

// Round to nearest, ties to even, as cvRound (the CPU's default rounding) does: adding and
// removing 1.5 * 2^23 leaves a float of magnitude below 2^22 rounded to an integer.
inline float roundToInteger(float x) {
  constexpr float kMagic = 12582912.0f;
  return (x + kMagic) - kMagic;  // not folded: the build neither reassociates nor contracts
}

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

void describe(const cv::Mat& smoothed, const std::vector<cv::KeyPoint>& keypoints, cv::Mat& descriptors,
              int first_row) {
  const std::array<BriefTest, 256>& tests = g_tests ? *g_tests : orbTests();
  const TestPoints& points = testPoints(tests);
  const int step = static_cast<int>(smoothed.step);
  alignas(64) int offset[512];
  for (size_t k = 0; k < keypoints.size(); ++k) {
    const cv::KeyPoint& kp = keypoints[k];
    // The rotation as cv::ORB rounds it: single-precision angle, cosine and sine, products and
    // sums, each point rounded to the nearest pixel; the loop is vectorised.
    const float angle = kp.angle * static_cast<float>(CV_PI / 180.f);
    const float a = std::cos(angle);
    const float b = std::sin(angle);
    for (int j = 0; j < 512; ++j) {
      const float ix = roundToInteger(points.x[j] * a - points.y[j] * b);
      const float iy = roundToInteger(points.x[j] * b + points.y[j] * a);
      offset[j] = static_cast<int>(iy) * step + static_cast<int>(ix);
    }
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
