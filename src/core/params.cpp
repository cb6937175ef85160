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

Params Params::paper() {
  Params p;
  p.enhance.tone_curve = ToneCurve::kGamma;
  p.enhance.alpha = 0.2;
  p.enhance.tau = 0.3;
  p.enhance.beta = 0.3;
  p.enhance.sharpening = 1.0;
  p.enhance.gamma_mode = GammaMode::kAuto;
  p.enhance.tone_tiles = 1;
  p.orb.max_features = 0;
  p.orb.candidate_ratio = 0.0;
  return p;
}

Params Params::preset(Preset preset) {
  return preset == Preset::kPaper ? paper() : Params();
}

Params Params::baseline(int fast_threshold) {
  Params p = paper();
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
  checkRange(out, "sharpening", p.sharpening, -1.0, 5.0);
  checkRange(out, "blur_ksize", p.blur_ksize, 1, 31);
  if (p.blur_ksize % 2 == 0) {
    out.push_back("blur_ksize = " + std::to_string(p.blur_ksize) + " must be odd");
  }
  checkRange(out, "blur_sigma", p.blur_sigma, 0.1, 10.0);
  checkRange(out, "std_threshold", p.std_threshold, 0.0, 1.0);
  checkRange(out, "tone_tiles", p.tone_tiles, 1, 16);
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
  checkRange(out, "candidate_ratio", p.candidate_ratio, 0.0, 100.0);
  return out;
}

std::vector<std::string> validate(const Params& p) {
  std::vector<std::string> out = validate(p.enhance);
  append(out, validate(p.threshold));
  append(out, validate(p.orb));
  return out;
}

namespace {

template <typename T>
bool parseWhole(const std::string& text, T& out) {
  std::istringstream in(text);
  T value{};
  in >> value;
  if (in.fail() || !in.eof()) {
    return false;
  }
  out = value;
  return true;
}

bool parseBool(const std::string& text, bool& out) {
  if (text == "true" || text == "1") {
    out = true;
  } else if (text == "false" || text == "0") {
    out = false;
  } else {
    return false;
  }
  return true;
}

}  // namespace

std::string setParam(Params& p, const std::string& name, const std::string& value) {
  EnhanceParams& e = p.enhance;
  ThresholdParams& t = p.threshold;
  OrbParams& o = p.orb;
  bool ok = false;
  if (name == "enhance") {
    ok = parseBool(value, p.enhance_enabled);
  } else if (name == "tone_curve") {
    ok = parseToneCurve(value, e.tone_curve);
  } else if (name == "alpha") {
    ok = parseWhole(value, e.alpha);
  } else if (name == "tau") {
    ok = parseWhole(value, e.tau);
  } else if (name == "beta") {
    ok = parseWhole(value, e.beta);
  } else if (name == "sharpening") {
    ok = parseWhole(value, e.sharpening);
  } else if (name == "blur_ksize") {
    ok = parseWhole(value, e.blur_ksize);
  } else if (name == "blur_sigma") {
    ok = parseWhole(value, e.blur_sigma);
  } else if (name == "std_threshold") {
    ok = parseWhole(value, e.std_threshold);
  } else if (name == "gamma_mode") {
    ok = parseGammaMode(value, e.gamma_mode);
  } else if (name == "tone_tiles") {
    ok = parseWhole(value, e.tone_tiles);
  } else if (name == "grid_size") {
    ok = parseWhole(value, t.grid_size);
  } else if (name == "threshold_scale") {
    ok = parseWhole(value, t.threshold_scale);
  } else if (name == "c_min") {
    ok = parseWhole(value, t.c_min);
  } else if (name == "threshold_mode") {
    ok = parseThresholdMode(value, o.threshold_mode);
  } else if (name == "fast_threshold") {
    ok = parseWhole(value, o.fast_threshold);
  } else if (name == "max_features") {
    ok = parseWhole(value, o.max_features);
  } else if (name == "n_levels") {
    ok = parseWhole(value, o.n_levels);
  } else if (name == "scale_factor") {
    ok = parseWhole(value, o.scale_factor);
  } else if (name == "candidate_ratio") {
    ok = parseWhole(value, o.candidate_ratio);
  } else {
    return "unknown parameter '" + name + "'";
  }
  return ok ? std::string() : "invalid value for " + name + ": '" + value + "'";
}

std::vector<std::string> inactiveParameters(const Params& p) {
  std::vector<std::string> out;
  const EnhanceParams& e = p.enhance;
  if (!p.enhance_enabled) {
    for (const char* name : {"tone_curve", "tone_tiles", "alpha", "tau", "beta", "sharpening", "blur_ksize",
                             "blur_sigma", "std_threshold", "gamma_mode"}) {
      out.push_back(std::string(name) + ": the enhancement is off");
    }
  } else {
    if (e.gamma_mode != GammaMode::kAuto) {
      out.push_back("std_threshold: only used when gamma_mode is auto");
    }
    if (e.tone_curve == ToneCurve::kGamma) {
      out.push_back("tone_tiles: only used when tone_curve is equalize");
    }
    if (e.gamma_mode == GammaMode::kNever) {
      for (const char* name : {"tone_curve", "tone_tiles", "alpha", "tau", "beta"}) {
        out.push_back(std::string(name) + ": the tone curve is off (gamma_mode never)");
      }
    }
  }
  if (p.orb.threshold_mode == ThresholdMode::kFixed) {
    for (const char* name : {"c_min", "threshold_scale"}) {
      out.push_back(std::string(name) + ": only used when threshold_mode is adaptive");
    }
  } else {
    out.push_back("fast_threshold: only used when threshold_mode is fixed");
  }
  if (p.orb.max_features == 0) {
    out.push_back("candidate_ratio: only used with a budget (max_features > 0)");
  }
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

const char* toString(ToneCurve curve) {
  return curve == ToneCurve::kGamma ? "gamma" : "equalize";
}

const char* toString(Preset preset) {
  return preset == Preset::kPaper ? "paper" : "default";
}

bool parseToneCurve(const std::string& name, ToneCurve& out) {
  for (ToneCurve c : {ToneCurve::kGamma, ToneCurve::kEqualize}) {
    if (name == toString(c)) {
      out = c;
      return true;
    }
  }
  return false;
}

bool parsePreset(const std::string& name, Preset& out) {
  for (Preset p : {Preset::kDefault, Preset::kPaper}) {
    if (name == toString(p)) {
      out = p;
      return true;
    }
  }
  return false;
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
