// libFuzzer target over the core library: image size, layout and pixels and every parameter come
// from the input. Invalid parameters must be rejected by validate() (and the constructor), valid
// ones must run, and every result must be well formed. Built and run by scripts/fuzz.sh.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <stdexcept>

#include <fuzzer/FuzzedDataProvider.h>

#include "enhanced_orb/enhance.h"
#include "enhanced_orb/orb_extractor.h"

namespace eo = enhanced_orb;

namespace {

// A value mostly in [lo, hi], sometimes a little outside it, sometimes NaN or infinite.
double anyDouble(FuzzedDataProvider& in, double lo, double hi) {
  switch (in.ConsumeIntegralInRange(0, 15)) {
    case 0:
      return std::numeric_limits<double>::quiet_NaN();
    case 1:
      return in.ConsumeBool() ? std::numeric_limits<double>::infinity() : -std::numeric_limits<double>::infinity();
    case 2:
      return in.ConsumeFloatingPointInRange(lo - 10.0, hi + 10.0);
    default:
      return in.ConsumeFloatingPointInRange(lo, hi);
  }
}

int anyInt(FuzzedDataProvider& in, int lo, int hi) {
  return in.ConsumeIntegralInRange(0, 15) == 0 ? in.ConsumeIntegralInRange(lo - 100, hi + 100)
                                               : in.ConsumeIntegralInRange(lo, hi);
}

// An invariant the result must keep: a finding when broken.
#define CHECK(condition)                                                               \
  do {                                                                                 \
    if (!(condition)) {                                                                \
      std::fprintf(stderr, "broken invariant at line %d: %s\n", __LINE__, #condition); \
      std::abort();                                                                    \
    }                                                                                  \
  } while (false)

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  eo::Params p;
  p.enhance_enabled = in.ConsumeBool();
  p.enhance.alpha = anyDouble(in, 0.0, 1.0);
  p.enhance.tau = anyDouble(in, 0.0, 1.0);
  p.enhance.beta = anyDouble(in, 0.0, 2.0);
  p.enhance.sharpening = anyDouble(in, -1.0, 5.0);
  p.enhance.tone_curve =
      in.PickValueInArray({eo::ToneCurve::kEqualize, eo::ToneCurve::kGamma, eo::ToneCurve::kStretch});
  p.enhance.blur_ksize = anyInt(in, 1, 31);
  p.enhance.blur_sigma = anyDouble(in, 0.1, 10.0);
  p.enhance.std_threshold = anyDouble(in, 0.0, 1.0);
  p.enhance.gamma_mode = static_cast<eo::GammaMode>(in.ConsumeIntegralInRange(0, 2));
  p.threshold.grid_size = anyInt(in, 1, 32);
  p.threshold.threshold_scale = anyDouble(in, 0.0, 2.0);
  p.threshold.c_min = anyInt(in, 1, 200);
  p.orb.threshold_mode = in.ConsumeBool() ? eo::ThresholdMode::kAdaptive : eo::ThresholdMode::kFixed;
  p.orb.fast_threshold = anyInt(in, 1, 200);
  p.orb.max_features = in.ConsumeBool() ? 0 : anyInt(in, 0, 3000);
  p.orb.n_levels = anyInt(in, 1, 16);
  p.orb.scale_factor = anyDouble(in, 1.01, 2.0);
  p.orb.candidate_ratio = anyDouble(in, 0.0, 100.0);

  const int width = in.ConsumeIntegralInRange(0, 320);
  const int height = in.ConsumeIntegralInRange(0, 240);
  const auto format = static_cast<eo::PixelFormat>(in.ConsumeIntegralInRange(0, 5));
  static const int kTypes[] = {CV_8UC1, CV_16UC1, CV_8UC3, CV_8UC3, CV_8UC4, CV_8UC4};
  cv::Mat image(height, width, kTypes[static_cast<int>(format)]);
  const std::vector<std::uint8_t> pixels = in.ConsumeRemainingBytes<std::uint8_t>();
  const size_t bytes = image.total() * image.elemSize();
  for (size_t i = 0; i < bytes; ++i) {  // the remaining input, repeated; zeros when there is none
    image.data[i] = pixels.empty() ? 0 : pixels[i % pixels.size()];
  }

  const cv::Mat gray = eo::toGray(image, format);  // the matching type never throws
  CHECK(gray.type() == CV_8UC1 && gray.size() == image.size());

  const bool valid = eo::validate(p).empty();
  try {
    const eo::OrbExtractor extractor(p);
    CHECK(valid);
    const eo::Extraction r = extractor.extract(gray);
    const int n = static_cast<int>(r.keypoints.size());
    CHECK(r.descriptors.rows == n && (n == 0 || r.descriptors.cols == eo::kDescriptorBytes));
    CHECK(r.cell_thresholds.rows == p.threshold.grid_size && r.cell_thresholds.cols == p.threshold.grid_size);
    CHECK(r.image.size() == gray.size());
    CHECK(p.orb.max_features == 0 || n <= p.orb.max_features);
    for (const cv::Mat& t : r.level_thresholds) {
      double lo = 0.0;
      cv::minMaxLoc(t, &lo);
      CHECK(lo >= (p.orb.threshold_mode == eo::ThresholdMode::kFixed ? p.orb.fast_threshold : p.threshold.c_min));
    }
    for (const cv::KeyPoint& kp : r.keypoints) {
      CHECK(kp.pt.x >= 0 && kp.pt.y >= 0 && kp.pt.x < gray.cols && kp.pt.y < gray.rows);
      CHECK(kp.octave >= 0 && kp.octave < p.orb.n_levels && kp.angle >= 0.0f && kp.angle < 360.0f);
    }
  } catch (const std::invalid_argument&) {
    CHECK(!valid);
  }
  return 0;
}
