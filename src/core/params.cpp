#include "enhanced_orb/params.h"

#include <sstream>

namespace enhanced_orb {
namespace {

// Appends a message when `value` lies outside [lo, hi]. NaN fails every comparison and is rejected.
template <typename T>
void checkRange(std::vector<std::string>& out, const char* name, T value, T lo, T hi) {
  if (value >= lo && value <= hi) {
    return;
  }
  std::ostringstream msg;
  msg << name << " = " << value << " is out of range [" << lo << ", " << hi << "]";
  out.push_back(msg.str());
}

void append(std::vector<std::string>& out, const std::vector<std::string>& more) {
  out.insert(out.end(), more.begin(), more.end());
}

}  // namespace

Params Params::baseline(int fast_threshold) {
  Params p;
  p.enhance_enabled = false;
  p.orb.threshold_mode = ThresholdMode::kFixed;
  p.orb.fast_threshold = fast_threshold;
  return p;
}

std::vector<std::string> validate(const EnhanceParams& p) {
  std::vector<std::string> out;
  checkRange(out, "alpha", p.alpha, 0.0, 1.0);
  checkRange(out, "tau", p.tau, 0.0, 1.0);
  checkRange(out, "beta", p.beta, 0.0, 2.0);
  checkRange(out, "sharpening", p.sharpening, 0.0, 5.0);
  checkRange(out, "blur_ksize", p.blur_ksize, 1, 31);
  if (p.blur_ksize % 2 == 0) {
    out.push_back("blur_ksize = " + std::to_string(p.blur_ksize) + " must be odd");
  }
  checkRange(out, "blur_sigma", p.blur_sigma, 0.1, 10.0);
  checkRange(out, "std_threshold", p.std_threshold, 0.0, 1.0);
  return out;
}

std::vector<std::string> validate(const ThresholdParams& p) {
  std::vector<std::string> out;
  checkRange(out, "grid_size", p.grid_size, 1, 32);
  checkRange(out, "threshold_scale", p.threshold_scale, 0.0, 2.0);
  checkRange(out, "c_min", p.c_min, 1, 200);
  return out;
}

std::vector<std::string> validate(const OrbParams& p) {
  std::vector<std::string> out;
  checkRange(out, "fast_threshold", p.fast_threshold, 1, 200);
  checkRange(out, "max_features", p.max_features, 0, 100000);
  checkRange(out, "n_levels", p.n_levels, 1, 16);
  checkRange(out, "scale_factor", p.scale_factor, 1.01, 2.0);
  return out;
}

std::vector<std::string> validate(const Params& p) {
  std::vector<std::string> out = validate(p.enhance);
  append(out, validate(p.threshold));
  append(out, validate(p.orb));
  return out;
}

std::string joinMessages(const std::vector<std::string>& messages) {
  std::string joined;
  for (const std::string& m : messages) {
    joined += (joined.empty() ? "" : "; ") + m;
  }
  return joined;
}

const char* toString(GammaMode mode) {
  switch (mode) {
    case GammaMode::kAlways:
      return "always";
    case GammaMode::kNever:
      return "never";
    case GammaMode::kAuto:
      break;
  }
  return "auto";
}

const char* toString(ThresholdMode mode) {
  return mode == ThresholdMode::kFixed ? "fixed" : "adaptive";
}

bool parseGammaMode(const std::string& name, GammaMode& out) {
  for (GammaMode m : {GammaMode::kAuto, GammaMode::kAlways, GammaMode::kNever}) {
    if (name == toString(m)) {
      out = m;
      return true;
    }
  }
  return false;
}

bool parseThresholdMode(const std::string& name, ThresholdMode& out) {
  for (ThresholdMode m : {ThresholdMode::kAdaptive, ThresholdMode::kFixed}) {
    if (name == toString(m)) {
      out = m;
      return true;
    }
  }
  return false;
}

}  // namespace enhanced_orb
