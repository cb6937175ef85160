// One source of truth: the dynamic_reconfigure defaults and ranges (cfg/*.cfg) agree with the core
// library's default mode (Params()) and its validation ranges (validate()).
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "enhanced_orb/EnhanceConfig.h"
#include "enhanced_orb/ExtractConfig.h"
#include "enhanced_orb/params.h"

using namespace enhanced_orb;

namespace {

// Whether validate() accepts `value` for the parameter `name`.
bool accepted(const std::string& name, const std::string& value) {
  Params p;
  EXPECT_EQ(setParam(p, name, value), "") << name << " = " << value;
  return validate(p).empty();
}

template <typename T>
void expectSameRange(const std::string& name, T lo, T hi) {
  EXPECT_TRUE(accepted(name, std::to_string(lo))) << name << " minimum " << lo;
  EXPECT_TRUE(accepted(name, std::to_string(hi))) << name << " maximum " << hi;
  if constexpr (std::is_integral_v<T>) {
    EXPECT_FALSE(accepted(name, std::to_string(lo - 1))) << name << " below " << lo;
    EXPECT_FALSE(accepted(name, std::to_string(hi + 1))) << name << " above " << hi;
  } else {
    EXPECT_FALSE(accepted(name, std::to_string(lo - 0.01))) << name << " below " << lo;
    EXPECT_FALSE(accepted(name, std::to_string(hi + 0.01))) << name << " above " << hi;
  }
}

}  // namespace

TEST(ConfigAgreement, EnhanceDefaultsAreTheDefaultMode) {
  const EnhanceConfig c = EnhanceConfig::__getDefault__();
  const EnhanceParams e;
  EXPECT_EQ(c.tone_curve, toString(e.tone_curve));
  EXPECT_DOUBLE_EQ(c.alpha, e.alpha);
  EXPECT_DOUBLE_EQ(c.tau, e.tau);
  EXPECT_DOUBLE_EQ(c.beta, e.beta);
  EXPECT_DOUBLE_EQ(c.sharpening, e.sharpening);
  EXPECT_EQ(c.blur_ksize, e.blur_ksize);
  EXPECT_DOUBLE_EQ(c.blur_sigma, e.blur_sigma);
  EXPECT_DOUBLE_EQ(c.std_threshold, e.std_threshold);
  EXPECT_EQ(c.gamma_mode, toString(e.gamma_mode));
  EXPECT_EQ(c.enhance_threads, e.threads);
  EXPECT_EQ(c.enhance, Params().enhance_enabled);
}

TEST(ConfigAgreement, ExtractDefaultsAreTheDefaultMode) {
  const ExtractConfig c = ExtractConfig::__getDefault__();
  const Params p;
  EXPECT_EQ(c.threshold_mode, toString(p.orb.threshold_mode));
  EXPECT_EQ(c.c_min, p.threshold.c_min);
  EXPECT_DOUBLE_EQ(c.threshold_scale, p.threshold.threshold_scale);
  EXPECT_EQ(c.grid_size, p.threshold.grid_size);
  EXPECT_EQ(c.fast_threshold, p.orb.fast_threshold);
  EXPECT_EQ(c.max_features, p.orb.max_features);
  EXPECT_DOUBLE_EQ(c.candidate_ratio, p.orb.candidate_ratio);
  EXPECT_DOUBLE_EQ(c.noise_floor, p.orb.noise_floor);
  EXPECT_EQ(c.n_levels, p.orb.n_levels);
  EXPECT_DOUBLE_EQ(c.scale_factor, p.orb.scale_factor);
  EXPECT_EQ(c.threads, p.orb.threads);
}

TEST(ConfigAgreement, RangesAreTheLibrarys) {
  const EnhanceConfig lo = EnhanceConfig::__getMin__(), hi = EnhanceConfig::__getMax__();
  expectSameRange("alpha", lo.alpha, hi.alpha);
  expectSameRange("tau", lo.tau, hi.tau);
  expectSameRange("beta", lo.beta, hi.beta);
  expectSameRange("sharpening", lo.sharpening, hi.sharpening);
  expectSameRange("blur_sigma", lo.blur_sigma, hi.blur_sigma);
  expectSameRange("std_threshold", lo.std_threshold, hi.std_threshold);
  expectSameRange("enhance_threads", lo.enhance_threads, hi.enhance_threads);
  EXPECT_TRUE(accepted("blur_ksize", std::to_string(lo.blur_ksize)));
  EXPECT_TRUE(accepted("blur_ksize", std::to_string(hi.blur_ksize)));
  const ExtractConfig xlo = ExtractConfig::__getMin__(), xhi = ExtractConfig::__getMax__();
  expectSameRange("c_min", xlo.c_min, xhi.c_min);
  expectSameRange("threshold_scale", xlo.threshold_scale, xhi.threshold_scale);
  expectSameRange("grid_size", xlo.grid_size, xhi.grid_size);
  expectSameRange("fast_threshold", xlo.fast_threshold, xhi.fast_threshold);
  expectSameRange("max_features", xlo.max_features, xhi.max_features);
  expectSameRange("candidate_ratio", xlo.candidate_ratio, xhi.candidate_ratio);
  expectSameRange("noise_floor", xlo.noise_floor, xhi.noise_floor);
  expectSameRange("n_levels", xlo.n_levels, xhi.n_levels);
  expectSameRange("scale_factor", xlo.scale_factor, xhi.scale_factor);
  expectSameRange("threads", xlo.threads, xhi.threads);
}
