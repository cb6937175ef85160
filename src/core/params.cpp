#include "enhanced_orb/params.h"

#include <functional>
#include <initializer_list>
#include <optional>
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
  p.enhance.blur_ksize = 5;
  p.orb.max_features = 0;
  p.orb.candidate_ratio = 0.0;
  return p;
}

Params Params::stretch() {
  Params p;
  p.enhance.tone_curve = ToneCurve::kStretch;
  p.enhance.tau = 0.05;
  p.orb.candidate_ratio = 1.0;
  return p;
}

Params Params::motion() {
  Params p;
  p.threshold.threshold_scale = 0.0;
  p.orb.noise_floor = 8.0;
  return p;
}

Params Params::preset(Preset preset) {
  switch (preset) {
    case Preset::kMotion:
      return motion();
    case Preset::kPaper:
      return paper();
    case Preset::kStretch:
      return stretch();
    case Preset::kDefault:
      break;
  }
  return Params();
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
  if (p.tone_curve == ToneCurve::kStretch && p.tau >= 0.5) {
    std::ostringstream msg;
    msg << "tau = " << p.tau << " must be below 0.5 with tone_curve stretch (it clips that fraction at each end)";
    out.push_back(msg.str());
  }
  checkRange(out, "beta", p.beta, 0.0, 2.0);
  checkRange(out, "sharpening", p.sharpening, -1.0, 5.0);
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
  checkRange(out, "candidate_ratio", p.candidate_ratio, 0.0, 100.0);
  checkRange(out, "noise_floor", p.noise_floor, 0.0, 50.0);
  checkRange(out, "threads", p.threads, 1, 64);
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

namespace {

// A parameter as text: read with parse, written with format. The one list of names the command
// line, the nodelets' preset seeding and the evaluation tools share.
struct Field {
  const char* name;
  std::function<bool(Params&, const std::string&)> parse;
  std::function<std::string(const Params&)> format;
};

template <typename T>
std::string formatNumber(T value) {
  std::ostringstream out;
  out.precision(17);  // doubles survive the round trip through text
  out << value;
  return out.str();
}

// A numeric field reached by `at` (which returns a reference into Params).
template <typename At>
Field number(const char* name, At at) {
  return {name, [at](Params& p, const std::string& v) { return parseWhole(v, at(p)); },
          [at](const Params& p) { return formatNumber(at(const_cast<Params&>(p))); }};
}

// A named-enum field.
template <typename At, typename Parse>
Field named(const char* name, At at, Parse parse) {
  return {name, [at, parse](Params& p, const std::string& v) { return parse(v, at(p)); },
          [at](const Params& p) { return std::string(toString(at(const_cast<Params&>(p)))); }};
}

const std::vector<Field>& fields() {
  static const std::vector<Field> all = {
      {"enhance", [](Params& p, const std::string& v) { return parseBool(v, p.enhance_enabled); },
       [](const Params& p) { return std::string(p.enhance_enabled ? "true" : "false"); }},
      named(
          "tone_curve", [](Params& p) -> ToneCurve& { return p.enhance.tone_curve; }, parseToneCurve),
      number("alpha", [](Params& p) -> double& { return p.enhance.alpha; }),
      number("tau", [](Params& p) -> double& { return p.enhance.tau; }),
      number("beta", [](Params& p) -> double& { return p.enhance.beta; }),
      number("sharpening", [](Params& p) -> double& { return p.enhance.sharpening; }),
      number("blur_ksize", [](Params& p) -> int& { return p.enhance.blur_ksize; }),
      number("blur_sigma", [](Params& p) -> double& { return p.enhance.blur_sigma; }),
      number("std_threshold", [](Params& p) -> double& { return p.enhance.std_threshold; }),
      named(
          "gamma_mode", [](Params& p) -> GammaMode& { return p.enhance.gamma_mode; }, parseGammaMode),
      number("grid_size", [](Params& p) -> int& { return p.threshold.grid_size; }),
      number("threshold_scale", [](Params& p) -> double& { return p.threshold.threshold_scale; }),
      number("c_min", [](Params& p) -> int& { return p.threshold.c_min; }),
      named(
          "threshold_mode", [](Params& p) -> ThresholdMode& { return p.orb.threshold_mode; }, parseThresholdMode),
      number("fast_threshold", [](Params& p) -> int& { return p.orb.fast_threshold; }),
      number("max_features", [](Params& p) -> int& { return p.orb.max_features; }),
      number("candidate_ratio", [](Params& p) -> double& { return p.orb.candidate_ratio; }),
      number("noise_floor", [](Params& p) -> double& { return p.orb.noise_floor; }),
      number("n_levels", [](Params& p) -> int& { return p.orb.n_levels; }),
      number("scale_factor", [](Params& p) -> double& { return p.orb.scale_factor; }),
      number("threads", [](Params& p) -> int& { return p.orb.threads; }),
  };
  return all;
}

const Field* findField(const std::string& name) {
  for (const Field& f : fields()) {
    if (name == f.name) {
      return &f;
    }
  }
  return nullptr;
}

}  // namespace

std::string setParam(Params& p, const std::string& name, const std::string& value) {
  const Field* field = findField(name);
  if (!field) {
    return "unknown parameter '" + name + "'";
  }
  return field->parse(p, value) ? std::string() : "invalid value for " + name + ": '" + value + "'";
}

std::vector<std::string> paramNames() {
  std::vector<std::string> names;
  for (const Field& f : fields()) {
    names.push_back(f.name);
  }
  return names;
}

std::optional<std::string> paramText(const Params& p, const std::string& name) {
  const Field* field = findField(name);
  return field ? std::optional<std::string>(field->format(p)) : std::nullopt;
}

std::vector<std::string> inactiveParameters(const Params& p) {
  std::vector<std::string> out;
  const EnhanceParams& e = p.enhance;
  if (!p.enhance_enabled) {
    for (const char* name : {"tone_curve", "alpha", "tau", "beta", "sharpening", "blur_ksize", "blur_sigma",
                             "std_threshold", "gamma_mode"}) {
      out.push_back(std::string(name) + ": the enhancement is off");
    }
  } else {
    if (e.gamma_mode != GammaMode::kAuto) {
      out.push_back("std_threshold: only used when gamma_mode is auto");
    }
    if (e.gamma_mode == GammaMode::kNever) {
      for (const char* name : {"tone_curve", "alpha", "tau", "beta"}) {
        out.push_back(std::string(name) + ": the tone curve is off (gamma_mode never)");
      }
    } else if (e.tone_curve == ToneCurve::kStretch) {
      out.push_back("alpha: not used by tone_curve stretch");
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
    out.push_back("noise_floor: only used with a budget (max_features > 0)");
  } else if (p.orb.noise_floor > 0.0) {
    out.push_back("candidate_ratio: not used when noise_floor > 0");
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

namespace {

// Every value of each named enum with its name: what toString() says, the parsers read and the
// name lists show.
template <typename Enum>
struct Named {
  Enum value;
  const char* name;
};
constexpr Named<ToneCurve> kToneCurves[] = {
    {ToneCurve::kGamma, "gamma"}, {ToneCurve::kEqualize, "equalize"}, {ToneCurve::kStretch, "stretch"}};
constexpr Named<Preset> kPresets[] = {{Preset::kDefault, "default"},
                                      {Preset::kPaper, "paper"},
                                      {Preset::kStretch, "stretch"},
                                      {Preset::kMotion, "motion"}};
constexpr Named<GammaMode> kGammaModes[] = {
    {GammaMode::kAuto, "auto"}, {GammaMode::kAlways, "always"}, {GammaMode::kNever, "never"}};
constexpr Named<ThresholdMode> kThresholdModes[] = {{ThresholdMode::kAdaptive, "adaptive"},
                                                    {ThresholdMode::kFixed, "fixed"}};

template <typename Enum, size_t N>
const char* nameOf(Enum value, const Named<Enum> (&table)[N]) {
  for (const Named<Enum>& entry : table) {
    if (entry.value == value) {
      return entry.name;
    }
  }
  return "?";
}

// The enum value whose name is `name`; false (and `out` unchanged) when none is.
template <typename Enum, size_t N>
bool parseName(const std::string& name, const Named<Enum> (&table)[N], Enum& out) {
  for (const Named<Enum>& entry : table) {
    if (name == entry.name) {
      out = entry.value;
      return true;
    }
  }
  return false;
}

// "a, b or c".
template <typename Enum, size_t N>
std::string nameList(const Named<Enum> (&table)[N]) {
  std::string list;
  for (size_t i = 0; i < N; ++i) {
    list += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(table[i].name);
  }
  return list;
}

}  // namespace

const char* toString(GammaMode mode) {
  return nameOf(mode, kGammaModes);
}

const char* toString(ThresholdMode mode) {
  return nameOf(mode, kThresholdModes);
}

const char* toString(ToneCurve curve) {
  return nameOf(curve, kToneCurves);
}

const char* toString(Preset preset) {
  return nameOf(preset, kPresets);
}

bool parseToneCurve(const std::string& name, ToneCurve& out) {
  return parseName(name, kToneCurves, out);
}

bool parsePreset(const std::string& name, Preset& out) {
  return parseName(name, kPresets, out);
}

bool parseGammaMode(const std::string& name, GammaMode& out) {
  return parseName(name, kGammaModes, out);
}

bool parseThresholdMode(const std::string& name, ThresholdMode& out) {
  return parseName(name, kThresholdModes, out);
}

std::string toneCurveNames() {
  return nameList(kToneCurves);
}

std::string presetNames() {
  return nameList(kPresets);
}

std::string gammaModeNames() {
  return nameList(kGammaModes);
}

std::string thresholdModeNames() {
  return nameList(kThresholdModes);
}

}  // namespace enhanced_orb
