#include "enhanced_orb/params.h"

#include <algorithm>
#include <functional>
#include <initializer_list>
#include <optional>
#include <sstream>
#include <type_traits>
#include <utility>

namespace enhanced_orb {
namespace {

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
  p.orb.camera_motion = MotionMode::kStill;
  return p;
}

Params Params::stretch() {
  Params p;
  p.enhance.tone_curve = ToneCurve::kStretch;
  p.enhance.tau = 0.05;
  p.orb.candidate_ratio = 1.0;
  p.orb.camera_motion = MotionMode::kStill;
  return p;
}

Params Params::motion() {
  Params p;
  p.orb.camera_motion = MotionMode::kMoving;
  return p;
}

bool Params::movingSelection(bool judged_moving) const {
  return orb.camera_motion == MotionMode::kMoving || (orb.camera_motion == MotionMode::kAuto && judged_moving);
}

Params Params::forFrame(bool judged_moving, double stream_lambda) const {
  Params p = *this;
  if (movingSelection(judged_moving)) {
    p.enhance.gamma_mode = enhance.moving_gamma_mode;
    if (p.enhance.gamma_mode == GammaMode::kAuto && stream_lambda >= 0.0) {
      // The quality test (section III-A, step 3) on the stream's frames rather than on this one.
      p.enhance.gamma_mode = stream_lambda > enhance.std_threshold ? GammaMode::kAlways : GammaMode::kNever;
    }
    p.threshold.threshold_scale = threshold.moving_threshold_scale;
    p.orb.noise_floor = orb.moving_noise_floor;
  }
  return p;
}

bool Params::enhancementJudgesStream() const {
  if (!enhance_enabled || orb.camera_motion == MotionMode::kStill) {
    return false;
  }
  return enhance.moving_gamma_mode == GammaMode::kAuto ||
         (orb.camera_motion == MotionMode::kAuto && enhance.moving_gamma_mode != enhance.gamma_mode);
}

bool Params::judgesStream() const {
  return orb.camera_motion == MotionMode::kAuto || enhancementJudgesStream();
}

Params Params::preset(Preset preset) {
  switch (preset) {
    case Preset::kMotion:
      return motion();
    case Preset::kPaper:
      return paper();
    case Preset::kStretch:
      return stretch();
    case Preset::kBaseline:
      return baseline();
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

// The parameter table: every parameter of Params once, with its ROS name, the part of Params it
// belongs to, how it is read and written as text, its range, its meaning and when it has no effect.
// setParam(), paramText(), paramNames(), validate()'s range checks, inactiveParameters() and
// paramTable() (the tools' usage text, the tests that hold cfg/*.cfg to it) all read it. Defaults
// are Params' member initialisers.
enum class Group { kSwitch, kEnhance, kThreshold, kOrb };

struct Field {
  const char* name;
  Group group;
  std::function<bool(Params&, const std::string&)> parse;
  std::function<std::string(const Params&)> format;
  const char* type;                            // "bool", "int", "double", or the names an enum reads
  double lo = 0.0, hi = 0.0;                   // the range (numbers only)
  std::function<double(const Params&)> value;  // the value as a number (numbers only)
  const char* meaning = "";
  // Why the parameter has no effect under a set of parameters, or nullptr when it has one.
  const char* (*unused)(const Params&) = nullptr;
};

// The reasons a parameter can have no effect, each checked in the order a field lists them.
const char* enhancementOff(const Params& p) {
  return p.enhance_enabled ? nullptr : "the enhancement is off";
}
// Whether a selection in use (camera_motion) runs the tone curve with gamma_mode `mode`.
bool gammaModeInUse(const Params& p, GammaMode mode) {
  return (p.orb.camera_motion != MotionMode::kMoving && p.enhance.gamma_mode == mode) ||
         (p.orb.camera_motion != MotionMode::kStill && p.enhance.moving_gamma_mode == mode);
}
const char* toneCurveOff(const Params& p) {
  const char* why = enhancementOff(p);
  return why ? why
         : !gammaModeInUse(p, GammaMode::kAuto) && !gammaModeInUse(p, GammaMode::kAlways)
             ? "the tone curve is off (gamma_mode, and moving_gamma_mode while the camera moves, never)"
             : nullptr;
}
const char* alphaUnused(const Params& p) {
  const char* why = toneCurveOff(p);
  return why ? why : p.enhance.tone_curve == ToneCurve::kStretch ? "not used by tone_curve stretch" : nullptr;
}
const char* qualityTestUnused(const Params& p) {
  const char* why = enhancementOff(p);
  return why                                    ? why
         : !gammaModeInUse(p, GammaMode::kAuto) ? "only used when gamma_mode or moving_gamma_mode is auto"
                                                : nullptr;
}
const char* adaptiveOnly(const Params& p) {
  return p.orb.threshold_mode == ThresholdMode::kFixed ? "only used when threshold_mode is adaptive" : nullptr;
}
const char* fixedOnly(const Params& p) {
  return p.orb.threshold_mode == ThresholdMode::kAdaptive ? "only used when threshold_mode is fixed" : nullptr;
}
const char* budgetOnly(const Params& p) {
  return p.orb.max_features == 0 ? "only used with a budget (max_features > 0)" : nullptr;
}
const char* stillUnused(const Params& p) {
  return p.orb.camera_motion == MotionMode::kMoving ? "not used when camera_motion is moving (the moving_ one is)"
                                                    : nullptr;
}
const char* movingUnused(const Params& p) {
  return p.orb.camera_motion == MotionMode::kStill ? "not used when camera_motion is still" : nullptr;
}
// The first of two reasons that applies.
const char* either(const char* first, const char* second) {
  return first ? first : second;
}
const char* gammaModeUnused(const Params& p) {
  return either(enhancementOff(p), stillUnused(p));
}
const char* movingGammaModeUnused(const Params& p) {
  return either(enhancementOff(p), movingUnused(p));
}
const char* thresholdScaleUnused(const Params& p) {
  return either(adaptiveOnly(p), stillUnused(p));
}
const char* movingThresholdScaleUnused(const Params& p) {
  return either(adaptiveOnly(p), movingUnused(p));
}
const char* noiseFloorUnused(const Params& p) {
  return either(budgetOnly(p), stillUnused(p));
}
const char* movingNoiseFloorUnused(const Params& p) {
  return either(budgetOnly(p), movingUnused(p));
}
// Whether a selection in use (the still camera's unless camera_motion is moving, the moving
// camera's unless it is still) has a noise floor above 0 (`with_floor`) or none.
bool selectionInUse(const Params& p, bool with_floor) {
  const bool still = p.orb.camera_motion != MotionMode::kMoving && (p.orb.noise_floor > 0.0) == with_floor;
  const bool moving = p.orb.camera_motion != MotionMode::kStill && (p.orb.moving_noise_floor > 0.0) == with_floor;
  return still || moving;
}
const char* candidateRatioUnused(const Params& p) {
  const char* why = budgetOnly(p);
  return why ? why : selectionInUse(p, false) ? nullptr : "not used when the noise floor in use is > 0";
}
const char* floorCandidateRatioUnused(const Params& p) {
  const char* why = budgetOnly(p);
  return why                       ? why
         : selectionInUse(p, true) ? nullptr
                                   : "only used with a noise floor above 0 (noise_floor, moving_noise_floor)";
}

template <typename T>
std::string formatNumber(T value) {
  std::ostringstream out;
  out.precision(17);  // doubles survive the round trip through text
  out << value;
  return out.str();
}

// A numeric field reached by `at` (which returns a reference into Params), valid in [lo, hi].
template <typename At>
Field number(const char* name, Group group, At at, double lo, double hi, const char* meaning,
             const char* (*unused)(const Params&) = nullptr) {
  using T = std::remove_reference_t<decltype(at(std::declval<Params&>()))>;
  return {name,
          group,
          [at](Params& p, const std::string& v) { return parseWhole(v, at(p)); },
          [at](const Params& p) { return formatNumber(at(const_cast<Params&>(p))); },
          std::is_integral_v<T> ? "int" : "double",
          lo,
          hi,
          [at](const Params& p) { return static_cast<double>(at(const_cast<Params&>(p))); },
          meaning,
          unused};
}

// A named-enum field.
template <typename At, typename Parse>
Field named(const char* name, Group group, At at, Parse parse, const char* type, const char* meaning,
            const char* (*unused)(const Params&) = nullptr) {
  return {name,
          group,
          [at, parse](Params& p, const std::string& v) { return parse(v, at(p)); },
          [at](const Params& p) { return std::string(toString(at(const_cast<Params&>(p)))); },
          type,
          0.0,
          0.0,
          nullptr,
          meaning,
          unused};
}

const std::vector<Field>& fields() {
  static const std::vector<Field> all = {
      {"enhance", Group::kSwitch, [](Params& p, const std::string& v) { return parseBool(v, p.enhance_enabled); },
       [](const Params& p) { return std::string(p.enhance_enabled ? "true" : "false"); }, "bool", 0.0, 0.0, nullptr,
       "false: the image is used as it is (already enhanced, or the original ORB)"},
      named(
          "tone_curve", Group::kEnhance, [](Params& p) -> ToneCurve& { return p.enhance.tone_curve; }, parseToneCurve,
          "equalize|gamma|stretch",
          "the tone curve of eqs 10-17: edge-weighted equalisation, the paper's gamma, a linear stretch", toneCurveOff),
      number(
          "alpha", Group::kEnhance, [](Params& p) -> double& { return p.enhance.alpha; }, 0.0, 1.0,
          "eq 12: smoothness exponent of the weighted histogram", alphaUnused),
      number(
          "tau", Group::kEnhance, [](Params& p) -> double& { return p.enhance.tau; }, 0.0, 1.0,
          "eq 15: lower truncation of gamma (equalize: least slope; stretch: fraction clipped at each end, < 0.5)",
          toneCurveOff),
      number(
          "beta", Group::kEnhance, [](Params& p) -> double& { return p.enhance.beta; }, 0.0, 2.0,
          "eq 20: weight of the brightness mask", toneCurveOff),
      number(
          "sharpening", Group::kEnhance, [](Params& p) -> double& { return p.enhance.sharpening; }, -1.0, 5.0,
          "eq 19: unsharp-mask degree; -1 keeps the filtered image", enhancementOff),
      number(
          "blur_ksize", Group::kEnhance, [](Params& p) -> int& { return p.enhance.blur_ksize; }, 1, 31,
          "eq 8: Gaussian kernel size, odd", enhancementOff),
      number(
          "blur_sigma", Group::kEnhance, [](Params& p) -> double& { return p.enhance.blur_sigma; }, 0.1, 10.0,
          "eq 8: Gaussian sigma", enhancementOff),
      number(
          "std_threshold", Group::kEnhance, [](Params& p) -> double& { return p.enhance.std_threshold; }, 0.0, 1.0,
          "quality test: the tone curve runs when lambda exceeds it (gamma_mode or moving_gamma_mode auto)",
          qualityTestUnused),
      named(
          "gamma_mode", Group::kEnhance, [](Params& p) -> GammaMode& { return p.enhance.gamma_mode; }, parseGammaMode,
          "auto|always|never", "when the tone curve runs: by the quality test, always, never", gammaModeUnused),
      named(
          "moving_gamma_mode", Group::kEnhance, [](Params& p) -> GammaMode& { return p.enhance.moving_gamma_mode; },
          parseGammaMode, "auto|always|never",
          "gamma_mode while the camera moves (camera_motion; auto: the quality test on the stream's last 5 frames)",
          movingGammaModeUnused),
      number(
          "enhance_threads", Group::kEnhance, [](Params& p) -> int& { return p.enhance.threads; }, 1, 64,
          "threads of one enhancement (the same result for any count)", enhancementOff),
      number(
          "grid_size", Group::kThreshold, [](Params& p) -> int& { return p.threshold.grid_size; }, 1, 32,
          "m: the image is cut into m x m cells, each with its own FAST threshold"),
      number(
          "threshold_scale", Group::kThreshold, [](Params& p) -> double& { return p.threshold.threshold_scale; }, 0.0,
          2.0, "a in C = a |I_mid - t| (eq 33)", thresholdScaleUnused),
      number(
          "moving_threshold_scale", Group::kThreshold,
          [](Params& p) -> double& { return p.threshold.moving_threshold_scale; }, 0.0, 2.0,
          "threshold_scale while the camera moves (camera_motion)", movingThresholdScaleUnused),
      number(
          "c_min", Group::kThreshold, [](Params& p) -> int& { return p.threshold.c_min; }, 1, 200,
          "C_min (eq 34): the least FAST threshold of a cell", adaptiveOnly),
      named(
          "threshold_mode", Group::kOrb, [](Params& p) -> ThresholdMode& { return p.orb.threshold_mode; },
          parseThresholdMode, "adaptive|fixed", "per-cell truncated adaptive thresholds, or one fixed threshold"),
      number(
          "fast_threshold", Group::kOrb, [](Params& p) -> int& { return p.orb.fast_threshold; }, 1, 200,
          "the fixed FAST threshold (threshold_mode fixed)", fixedOnly),
      number(
          "max_features", Group::kOrb, [](Params& p) -> int& { return p.orb.max_features; }, 0, 100000,
          "the budget over all levels; 0 keeps every corner"),
      number(
          "candidate_ratio", Group::kOrb, [](Params& p) -> double& { return p.orb.candidate_ratio; }, 0.0, 100.0,
          "a level spreads its budget over its candidate_ratio x budget strongest corners; 0: over all",
          candidateRatioUnused),
      number(
          "noise_floor", Group::kOrb, [](Params& p) -> double& { return p.orb.noise_floor; }, 0.0, 50.0,
          "> 0: a level spreads its budget over its corners scoring noise_floor x the frame's noise or more",
          noiseFloorUnused),
      number(
          "moving_noise_floor", Group::kOrb, [](Params& p) -> double& { return p.orb.moving_noise_floor; }, 0.0, 50.0,
          "noise_floor while the camera moves (camera_motion)", movingNoiseFloorUnused),
      number(
          "floor_candidate_ratio", Group::kOrb, [](Params& p) -> double& { return p.orb.floor_candidate_ratio; }, 0.0,
          100.0,
          "> 0: of a level's corners above the noise floor, its floor_candidate_ratio x budget strongest at most",
          floorCandidateRatioUnused),
      named(
          "camera_motion", Group::kOrb, [](Params& p) -> MotionMode& { return p.orb.camera_motion; }, parseMotionMode,
          "auto|still|moving",
          "which selection a frame gets: judged from the stream's frames, the still camera's, the moving camera's"),
      number(
          "n_levels", Group::kOrb, [](Params& p) -> int& { return p.orb.n_levels; }, 1, 16, "pyramid levels"),
      number(
          "scale_factor", Group::kOrb, [](Params& p) -> double& { return p.orb.scale_factor; }, 1.01, 2.0,
          "pyramid scale between levels"),
      number(
          "threads", Group::kOrb, [](Params& p) -> int& { return p.orb.threads; }, 1, 64,
          "threads of one extraction's pyramid levels (the same results for any count)"),
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

namespace {

// The range checks of one group of the table, on `p`: one message per value outside its range
// ("alpha = 1.5 is out of range [0, 1]"). NaN fails every comparison and is rejected.
std::vector<std::string> checkRanges(const Params& p, Group group) {
  std::vector<std::string> out;
  for (const Field& f : fields()) {
    if (f.group != group || !f.value) {
      continue;
    }
    const double v = f.value(p);
    if (v >= f.lo && v <= f.hi) {
      continue;
    }
    std::ostringstream msg;
    msg << f.name << " = " << v << " is out of range [" << f.lo << ", " << f.hi << "]";
    out.push_back(msg.str());
  }
  return out;
}

}  // namespace

std::vector<std::string> validate(const EnhanceParams& e) {
  Params p;
  p.enhance = e;
  std::vector<std::string> out = checkRanges(p, Group::kEnhance);
  if (e.tone_curve == ToneCurve::kStretch && e.tau >= 0.5) {
    std::ostringstream msg;
    msg << "tau = " << e.tau << " must be below 0.5 with tone_curve stretch (it clips that fraction at each end)";
    out.push_back(msg.str());
  }
  if (e.blur_ksize % 2 == 0) {
    out.push_back("blur_ksize = " + std::to_string(e.blur_ksize) + " must be odd");
  }
  return out;
}

std::vector<std::string> validate(const ThresholdParams& t) {
  Params p;
  p.threshold = t;
  return checkRanges(p, Group::kThreshold);
}

std::vector<std::string> validate(const OrbParams& o) {
  Params p;
  p.orb = o;
  return checkRanges(p, Group::kOrb);
}

std::vector<std::string> validate(const Params& p) {
  std::vector<std::string> out = validate(p.enhance);
  append(out, validate(p.threshold));
  append(out, validate(p.orb));
  return out;
}

std::vector<ParamInfo> paramTable() {
  std::vector<ParamInfo> table;
  const Params defaults;
  for (const Field& f : fields()) {
    ParamInfo info;
    info.name = f.name;
    info.type = f.type;
    info.has_range = static_cast<bool>(f.value);
    info.lo = f.lo;
    info.hi = f.hi;
    if (f.value) {
      std::ostringstream text;  // six significant digits: what a person reads (0.3, not 0.2999...)
      text << f.value(defaults);
      info.default_text = text.str();
    } else {
      info.default_text = f.format(defaults);
    }
    info.meaning = f.meaning;
    table.push_back(info);
  }
  return table;
}

std::string paramUsage() {
  std::ostringstream out;
  for (const ParamInfo& info : paramTable()) {
    std::string option = "--" + info.name;
    std::replace(option.begin(), option.end(), '_', '-');
    out << "  " << option << " ";
    if (info.has_range) {
      out << (info.type == "int" ? "N" : "X") << " in [" << info.lo << ", " << info.hi << "]";
    } else {
      out << info.type;
    }
    out << " (default " << info.default_text << ")\n      " << info.meaning << "\n";
  }
  return out.str();
}

std::string setParam(Params& p, const std::string& name, const std::string& value) {
  const Field* field = findField(name);
  if (!field) {
    return "unknown parameter '" + name + "'";
  }
  if (field->parse(p, value)) {
    return "";
  }
  // "<name> '<value>' is not ...": the name first, as in validate()'s messages.
  const std::string type = field->type;
  const std::string wanted = type == "int"      ? "a whole number"
                             : type == "double" ? "a number"
                             : type == "bool"   ? "true or false"
                                                : type;  // the names an enum reads
  return name + " '" + value + "' is not " + wanted;
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
  for (const Field& f : fields()) {
    if (const char* why = f.unused ? f.unused(p) : nullptr) {
      out.push_back(std::string(f.name) + ": " + why);
    }
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
                                      {Preset::kMotion, "motion"},
                                      {Preset::kBaseline, "baseline"}};
constexpr Named<GammaMode> kGammaModes[] = {
    {GammaMode::kAuto, "auto"}, {GammaMode::kAlways, "always"}, {GammaMode::kNever, "never"}};
constexpr Named<MotionMode> kMotionModes[] = {
    {MotionMode::kAuto, "auto"}, {MotionMode::kStill, "still"}, {MotionMode::kMoving, "moving"}};
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

const char* toString(MotionMode mode) {
  return nameOf(mode, kMotionModes);
}

bool parseMotionMode(const std::string& name, MotionMode& out) {
  return parseName(name, kMotionModes, out);
}

std::string motionModeNames() {
  return nameList(kMotionModes);
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
