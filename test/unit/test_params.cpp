#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "enhanced_orb/params.h"

using namespace enhanced_orb;

namespace {

// The single message of a validation that must fail on one parameter.
std::string onlyMessage(const std::vector<std::string>& messages) {
  EXPECT_EQ(messages.size(), 1u);
  return messages.empty() ? "" : messages.front();
}

}  // namespace

TEST(Params, PaperPresetIsThePapersAndValid) {
  const Params p = Params::paper();
  EXPECT_EQ(p.enhance.tone_curve, ToneCurve::kGamma);
  EXPECT_DOUBLE_EQ(p.orb.candidate_ratio, 0.0);
  EXPECT_DOUBLE_EQ(p.enhance.alpha, 0.2);
  EXPECT_DOUBLE_EQ(p.enhance.tau, 0.3);
  EXPECT_DOUBLE_EQ(p.enhance.beta, 0.3);
  EXPECT_DOUBLE_EQ(p.enhance.sharpening, 1.0);
  EXPECT_EQ(p.enhance.blur_ksize, 5);
  EXPECT_DOUBLE_EQ(p.enhance.blur_sigma, 1.0);
  EXPECT_DOUBLE_EQ(p.enhance.std_threshold, 0.25);
  EXPECT_EQ(p.enhance.gamma_mode, GammaMode::kAuto);
  EXPECT_EQ(p.threshold.grid_size, 5);
  EXPECT_DOUBLE_EQ(p.threshold.threshold_scale, 0.3);
  EXPECT_EQ(p.threshold.c_min, 7);
  EXPECT_EQ(p.orb.fast_threshold, 20);
  EXPECT_EQ(p.orb.max_features, 0);
  EXPECT_TRUE(p.enhance_enabled);
  EXPECT_EQ(p.orb.threshold_mode, ThresholdMode::kAdaptive);
  EXPECT_TRUE(validate(p).empty()) << joinMessages(validate(p));
}

TEST(Params, BaselineIsFixedThresholdWithoutEnhancement) {
  const Params p = Params::baseline();
  EXPECT_FALSE(p.enhance_enabled);
  EXPECT_EQ(p.orb.threshold_mode, ThresholdMode::kFixed);
  EXPECT_EQ(p.orb.fast_threshold, 20);
  EXPECT_EQ(Params::baseline(35).orb.fast_threshold, 35);
  EXPECT_TRUE(validate(p).empty());
}

TEST(Params, MessageNamesParameterValueAndRange) {
  EnhanceParams e;
  e.alpha = 1.5;
  EXPECT_EQ(onlyMessage(validate(e)), "alpha = 1.5 is out of range [0, 1]");
  ThresholdParams t;
  t.c_min = 0;
  EXPECT_EQ(onlyMessage(validate(t)), "c_min = 0 is out of range [1, 200]");
  OrbParams o;
  o.scale_factor = 1.0;
  EXPECT_EQ(onlyMessage(validate(o)), "scale_factor = 1 is out of range [1.01, 2]");
}

TEST(Params, EveryOutOfRangeValueIsRejected) {
  auto rejects = [](auto mutate, const std::string& name) {
    Params p;
    mutate(p);
    const std::string all = joinMessages(validate(p));
    EXPECT_NE(all.find(name), std::string::npos) << "expected a message about " << name << ", got '" << all << "'";
  };
  rejects([](Params& p) { p.enhance.alpha = -0.1; }, "alpha");
  rejects([](Params& p) { p.enhance.tau = 1.01; }, "tau");
  rejects([](Params& p) { p.enhance.beta = -1; }, "beta");
  rejects([](Params& p) { p.enhance.sharpening = 6; }, "sharpening");
  rejects([](Params& p) { p.enhance.blur_ksize = 33; }, "blur_ksize");
  rejects([](Params& p) { p.enhance.blur_ksize = 4; }, "blur_ksize = 4 must be odd");
  rejects([](Params& p) { p.enhance.blur_sigma = 0; }, "blur_sigma");
  rejects([](Params& p) { p.enhance.std_threshold = 2; }, "std_threshold");
  rejects([](Params& p) { p.threshold.grid_size = 0; }, "grid_size");
  rejects([](Params& p) { p.threshold.threshold_scale = 3; }, "threshold_scale");
  rejects([](Params& p) { p.threshold.c_min = 201; }, "c_min");
  rejects([](Params& p) { p.orb.fast_threshold = 0; }, "fast_threshold");
  rejects([](Params& p) { p.orb.max_features = -1; }, "max_features");
  rejects([](Params& p) { p.orb.n_levels = 17; }, "n_levels");
  rejects([](Params& p) { p.orb.scale_factor = 2.5; }, "scale_factor");
}

TEST(Params, NotANumberIsRejected) {
  Params p;
  p.enhance.beta = std::numeric_limits<double>::quiet_NaN();
  p.orb.scale_factor = std::numeric_limits<double>::infinity();
  EXPECT_EQ(validate(p).size(), 2u);
}

TEST(Params, ModeNamesRoundTrip) {
  for (GammaMode m : {GammaMode::kAuto, GammaMode::kAlways, GammaMode::kNever}) {
    GammaMode parsed = GammaMode::kAuto;
    ASSERT_TRUE(parseGammaMode(toString(m), parsed));
    EXPECT_EQ(parsed, m);
  }
  for (ThresholdMode m : {ThresholdMode::kAdaptive, ThresholdMode::kFixed}) {
    ThresholdMode parsed = ThresholdMode::kAdaptive;
    ASSERT_TRUE(parseThresholdMode(toString(m), parsed));
    EXPECT_EQ(parsed, m);
  }
  GammaMode unchanged = GammaMode::kNever;
  EXPECT_FALSE(parseGammaMode("sometimes", unchanged));
  EXPECT_EQ(unchanged, GammaMode::kNever);
}

TEST(Params, DefaultModeIsValidAndDiffersFromThePaperWhereDocumented) {
  const Params p;
  EXPECT_TRUE(validate(p).empty()) << joinMessages(validate(p));
  EXPECT_EQ(p.enhance.tone_curve, ToneCurve::kEqualize);
  EXPECT_EQ(p.enhance.gamma_mode, GammaMode::kAlways);
  EXPECT_DOUBLE_EQ(p.enhance.sharpening, -1.0);  // no unsharp mask: E = f + beta T_mask
  EXPECT_EQ(p.orb.max_features, 1000);
  EXPECT_GT(p.orb.candidate_ratio, 1.0);
  EXPECT_DOUBLE_EQ(p.orb.noise_floor, 0.0);
  // The threshold stage is the paper's.
  EXPECT_EQ(p.threshold.c_min, Params::paper().threshold.c_min);
  EXPECT_EQ(p.threshold.grid_size, Params::paper().threshold.grid_size);
  EXPECT_EQ(Params::preset(Preset::kPaper).enhance.tone_curve, ToneCurve::kGamma);
  EXPECT_EQ(Params::preset(Preset::kDefault).enhance.tone_curve, ToneCurve::kEqualize);
}

TEST(Params, StretchPresetIsTheDefaultModeWithTheRawToneOrder) {
  const Params s = Params::preset(Preset::kStretch);
  EXPECT_TRUE(validate(s).empty()) << joinMessages(validate(s));
  EXPECT_EQ(s.enhance.tone_curve, ToneCurve::kStretch);
  EXPECT_DOUBLE_EQ(s.enhance.tau, 0.05);
  EXPECT_DOUBLE_EQ(s.orb.candidate_ratio, 1.0);
  // Everything else is the default mode's.
  Params d;
  d.enhance.tone_curve = s.enhance.tone_curve;
  d.enhance.tau = s.enhance.tau;
  d.orb.candidate_ratio = s.orb.candidate_ratio;
  for (const char* name :
       {"enhance", "alpha", "beta", "sharpening", "blur_ksize", "blur_sigma", "gamma_mode", "grid_size",
        "threshold_scale", "c_min", "threshold_mode", "max_features", "n_levels", "scale_factor"}) {
    EXPECT_EQ(paramText(s, name), paramText(d, name)) << name;
  }
}

TEST(Params, BaselineIsThePaperWithoutEnhancement) {
  const Params b = Params::baseline();
  EXPECT_FALSE(b.enhance_enabled);
  EXPECT_EQ(b.orb.threshold_mode, ThresholdMode::kFixed);
  EXPECT_DOUBLE_EQ(b.orb.candidate_ratio, 0.0);
}

TEST(Params, SetParamByNameParsesWholeValuesOnly) {
  Params p;
  EXPECT_EQ(setParam(p, "alpha", "0.7"), "");
  EXPECT_DOUBLE_EQ(p.enhance.alpha, 0.7);
  EXPECT_EQ(setParam(p, "tone_curve", "gamma"), "");
  EXPECT_EQ(p.enhance.tone_curve, ToneCurve::kGamma);
  EXPECT_EQ(setParam(p, "c_min", "12"), "");
  EXPECT_EQ(p.threshold.c_min, 12);
  EXPECT_EQ(setParam(p, "enhance", "false"), "");
  EXPECT_FALSE(p.enhance_enabled);
  EXPECT_NE(setParam(p, "c_min", "12.5"), "");
  EXPECT_EQ(p.threshold.c_min, 12);
  EXPECT_NE(setParam(p, "alpha", "abc"), "");
  EXPECT_NE(setParam(p, "tone_curve", "clahe"), "");
  // The parameter's name comes first (the nodelets restore a refused value by it), then what it takes.
  EXPECT_EQ(setParam(p, "tone_curve", "clahe"), "tone_curve 'clahe' is not equalize|gamma|stretch");
  EXPECT_EQ(setParam(p, "c_min", "12.5"), "c_min '12.5' is not a whole number");
  EXPECT_NE(setParam(p, "no_such_parameter", "1"), "");
  EXPECT_EQ(setParam(p, "candidate_ratio", "101"), "");  // parsed; validate() rejects the range
  EXPECT_FALSE(validate(p).empty());
}

TEST(Params, NamesRoundTrip) {
  for (Preset preset : {Preset::kDefault, Preset::kPaper, Preset::kStretch, Preset::kMotion, Preset::kBaseline}) {
    Preset parsed = Preset::kDefault;
    ASSERT_TRUE(parsePreset(toString(preset), parsed));
    EXPECT_EQ(parsed, preset);
  }
  for (ToneCurve curve : {ToneCurve::kGamma, ToneCurve::kEqualize, ToneCurve::kStretch}) {
    ToneCurve parsed = ToneCurve::kGamma;
    ASSERT_TRUE(parseToneCurve(toString(curve), parsed));
    EXPECT_EQ(parsed, curve);
  }
  // The name lists of the messages hold every name the parsers read, and only those.
  auto names = [](const std::string& list) {
    std::vector<std::string> out;
    std::string rest = list;
    for (const std::string sep : {", ", " or "}) {
      size_t at;
      while ((at = rest.find(sep)) != std::string::npos) {
        out.push_back(rest.substr(0, at));
        rest = rest.substr(at + sep.size());
      }
    }
    out.push_back(rest);
    return out;
  };
  const std::vector<std::string> presets = names(presetNames());
  ASSERT_EQ(presets.size(), 5u) << presetNames();
  for (const std::string& name : presets) {
    Preset parsed;
    EXPECT_TRUE(parsePreset(name, parsed)) << name;
  }
  const std::vector<std::string> curves = names(toneCurveNames());
  ASSERT_EQ(curves.size(), 3u) << toneCurveNames();
  for (const std::string& name : curves) {
    ToneCurve parsed;
    EXPECT_TRUE(parseToneCurve(name, parsed)) << name;
  }
  EXPECT_EQ(names(gammaModeNames()).size(), 3u) << gammaModeNames();
  EXPECT_EQ(thresholdModeNames(), "adaptive or fixed");
  Preset unchanged = Preset::kPaper;
  EXPECT_FALSE(parsePreset("fast", unchanged));
  EXPECT_EQ(unchanged, Preset::kPaper);
}

TEST(Params, InactiveParametersAreNamedWithTheirReason) {
  auto has = [](const std::vector<std::string>& list, const std::string& name) {
    for (const std::string& s : list) {
      if (s.rfind(name + ":", 0) == 0) {
        return true;
      }
    }
    return false;
  };
  const std::vector<std::string> def = inactiveParameters(Params());
  EXPECT_TRUE(has(def, "std_threshold"));  // gamma_mode always, moving_gamma_mode never
  Params tested;
  tested.enhance.moving_gamma_mode = GammaMode::kAuto;
  EXPECT_FALSE(has(inactiveParameters(tested), "std_threshold"));  // a moving camera's frames tested
  Params still_only;
  still_only.orb.camera_motion = MotionMode::kStill;
  EXPECT_TRUE(has(inactiveParameters(still_only), "std_threshold"));      // gamma_mode always
  EXPECT_TRUE(has(inactiveParameters(still_only), "moving_gamma_mode"));  // never moving
  EXPECT_TRUE(has(inactiveParameters(Params::motion()), "gamma_mode"));   // always moving
  EXPECT_TRUE(has(inactiveParameters(Params::motion()), "alpha"));        // no tone curve while moving
  Params motion_tested = Params::motion();
  motion_tested.enhance.moving_gamma_mode = GammaMode::kAuto;
  EXPECT_FALSE(has(inactiveParameters(motion_tested), "std_threshold"));
  EXPECT_TRUE(has(def, "fast_threshold"));
  EXPECT_FALSE(has(def, "alpha"));
  EXPECT_FALSE(has(def, "tau"));
  EXPECT_FALSE(has(def, "beta"));
  EXPECT_FALSE(has(def, "c_min"));
  EXPECT_FALSE(has(def, "candidate_ratio"));
  const std::vector<std::string> paper = inactiveParameters(Params::paper());
  EXPECT_FALSE(has(paper, "std_threshold"));
  EXPECT_TRUE(has(paper, "candidate_ratio"));  // every corner
  const std::vector<std::string> base = inactiveParameters(Params::baseline());
  EXPECT_TRUE(has(base, "c_min"));
  EXPECT_TRUE(has(base, "alpha"));
  EXPECT_FALSE(has(base, "fast_threshold"));
  Params stretch;
  stretch.enhance.tone_curve = ToneCurve::kStretch;
  const std::vector<std::string> st = inactiveParameters(stretch);
  EXPECT_TRUE(has(st, "alpha"));  // the stretch reads quantiles only
  EXPECT_FALSE(has(st, "tau"));
  EXPECT_FALSE(has(st, "beta"));
  // With the enhancement off every parameter of the enhancement is inactive, and nothing else is
  // added for it; each named once.
  Params off;
  off.enhance_enabled = false;
  const std::vector<std::string> none = inactiveParameters(off);
  for (const char* name : {"tone_curve", "alpha", "tau", "beta", "sharpening", "blur_ksize", "blur_sigma",
                           "std_threshold", "gamma_mode", "moving_gamma_mode", "enhance_threads"}) {
    EXPECT_EQ(std::count_if(none.begin(), none.end(),
                            [&](const std::string& s) {
                              return s.rfind(std::string(name) + ": the enhancement is off", 0) == 0;
                            }),
              1)
        << name;
  }
  EXPECT_FALSE(has(none, "enhance"));
  Params never;
  never.enhance.gamma_mode = GammaMode::kNever;
  never.enhance.moving_gamma_mode = GammaMode::kAuto;
  EXPECT_FALSE(has(inactiveParameters(never), "alpha"));  // a moving camera's frame may still get the curve
  never.enhance.moving_gamma_mode = GammaMode::kNever;
  const std::vector<std::string> flat = inactiveParameters(never);
  EXPECT_TRUE(has(flat, "tone_curve") && has(flat, "alpha") && has(flat, "tau") && has(flat, "beta"));
  EXPECT_FALSE(has(flat, "sharpening"));
  // The moving camera's selection only: its noise floor decides, the still camera's parameters rest.
  const std::vector<std::string> motion = inactiveParameters(Params::motion());
  EXPECT_TRUE(has(motion, "candidate_ratio") && has(motion, "noise_floor") && has(motion, "threshold_scale"));
  EXPECT_FALSE(has(motion, "moving_noise_floor") || has(motion, "moving_threshold_scale"));
  // The default judges the camera: both selections can run, and the still one reads candidate_ratio.
  const std::vector<std::string> automatic = inactiveParameters(Params());
  EXPECT_FALSE(has(automatic, "candidate_ratio") || has(automatic, "noise_floor") ||
               has(automatic, "moving_noise_floor") || has(automatic, "moving_threshold_scale"));
  const std::vector<std::string> still = inactiveParameters(Params::paper());
  EXPECT_TRUE(has(still, "moving_threshold_scale") && !has(still, "threshold_scale"));
}

TEST(Params, StretchClipsLessThanHalfAtEachEnd) {
  Params p;
  p.enhance.tone_curve = ToneCurve::kStretch;
  p.enhance.tau = 0.49;
  EXPECT_TRUE(validate(p).empty());
  p.enhance.tau = 0.5;  // in [0, 1], but nothing would be left between the quantiles
  const std::vector<std::string> problems = validate(p);
  ASSERT_EQ(problems.size(), 1u);
  EXPECT_NE(problems[0].find("tau = 0.5"), std::string::npos) << problems[0];
  EXPECT_NE(problems[0].find("stretch"), std::string::npos) << problems[0];
  p.enhance.tone_curve = ToneCurve::kEqualize;
  EXPECT_TRUE(validate(p).empty());
}

TEST(Params, ParamTextReadsBackToTheSameValue) {
  const char* names[] = {"enhance",
                         "tone_curve",
                         "alpha",
                         "tau",
                         "beta",
                         "sharpening",
                         "blur_ksize",
                         "blur_sigma",
                         "std_threshold",
                         "gamma_mode",
                         "grid_size",
                         "threshold_scale",
                         "c_min",
                         "threshold_mode",
                         "fast_threshold",
                         "max_features",
                         "candidate_ratio",
                         "n_levels",
                         "scale_factor"};
  for (const Params& from : {Params(), Params::paper(), Params::baseline()}) {
    Params to;
    to.enhance.alpha = 0.123;  // differs from every preset, so that a missed field shows
    for (const char* name : names) {
      const std::optional<std::string> text = paramText(from, name);
      ASSERT_TRUE(text) << name;
      EXPECT_EQ(setParam(to, name, *text), "") << name << " = " << *text;
      EXPECT_EQ(paramText(to, name), text) << name;
    }
    EXPECT_DOUBLE_EQ(to.enhance.alpha, from.enhance.alpha);
    EXPECT_DOUBLE_EQ(to.orb.candidate_ratio, from.orb.candidate_ratio);
    EXPECT_EQ(to.enhance.tone_curve, from.enhance.tone_curve);
    EXPECT_EQ(to.enhance_enabled, from.enhance_enabled);
  }
  EXPECT_FALSE(paramText(Params(), "draw_grid"));
}

TEST(Params, NoiseFloorIsAParameterLikeTheOthers) {
  Params p;
  EXPECT_EQ(p.orb.noise_floor, 0.0);
  EXPECT_EQ(setParam(p, "noise_floor", "8"), "");
  EXPECT_DOUBLE_EQ(p.orb.noise_floor, 8.0);
  EXPECT_EQ(paramText(p, "noise_floor").value_or(""), "8");
  EXPECT_NE(setParam(p, "noise_floor", "loud"), "");
  auto inactive = [](const Params& q, const std::string& prefix) {
    for (const std::string& m : inactiveParameters(q)) {
      if (m.rfind(prefix, 0) == 0) {
        return true;
      }
    }
    return false;
  };
  p.orb.camera_motion = MotionMode::kStill;
  EXPECT_TRUE(inactive(p, "candidate_ratio: not used when the noise floor in use"));
  p.orb.noise_floor = 51.0;
  ASSERT_EQ(validate(p).size(), 1u);
  EXPECT_NE(validate(p)[0].find("noise_floor"), std::string::npos);
  p.orb.noise_floor = -1.0;
  EXPECT_EQ(validate(p).size(), 1u);
  p = Params();
  p.orb.max_features = 0;
  EXPECT_TRUE(inactive(p, "noise_floor: only used with a budget"));
  // floor_candidate_ratio qualifies a noise floor: unused where no selection in use has one.
  p = Params();
  EXPECT_FALSE(inactive(p, "floor_candidate_ratio"));  // the moving selection's floor, 8
  p.orb.camera_motion = MotionMode::kStill;
  EXPECT_TRUE(inactive(p, "floor_candidate_ratio: only used with a noise floor"));
  p.orb.noise_floor = 8.0;
  EXPECT_FALSE(inactive(p, "floor_candidate_ratio"));
  EXPECT_EQ(setParam(p, "floor_candidate_ratio", "8"), "");
  EXPECT_DOUBLE_EQ(p.orb.floor_candidate_ratio, 8.0);
  EXPECT_TRUE(validate(p).empty());
  p.orb.floor_candidate_ratio = 101.0;
  ASSERT_EQ(validate(p).size(), 1u);
  EXPECT_NE(validate(p)[0].find("floor_candidate_ratio"), std::string::npos);
}

// Every parameter by its name, as text: the same value whichever way it was reached.
std::map<std::string, std::string> asText(const Params& p) {
  std::map<std::string, std::string> out;
  for (const std::string& name : paramNames()) {
    out[name] = paramText(p, name).value_or("?");
  }
  return out;
}

TEST(Params, MotionPresetIsTheDefaultModeWithTheMovingSelection) {
  const Params m = Params::preset(Preset::kMotion);
  EXPECT_TRUE(validate(m).empty()) << joinMessages(validate(m));
  EXPECT_EQ(m.orb.camera_motion, MotionMode::kMoving);
  Preset parsed = Preset::kDefault;
  EXPECT_TRUE(parsePreset("motion", parsed));
  EXPECT_EQ(parsed, Preset::kMotion);
  Params d;
  d.orb.camera_motion = MotionMode::kMoving;
  EXPECT_EQ(asText(m), asText(d));
  // Every frame, judged or not, gets the moving selection: the noise floor and every cell at c_min.
  for (bool judged : {false, true}) {
    const Params frame = m.forFrame(judged);
    EXPECT_DOUBLE_EQ(frame.orb.noise_floor, 8.0);
    EXPECT_DOUBLE_EQ(frame.threshold.threshold_scale, 0.0);
  }
}

TEST(Params, CameraMotionChoosesTheSelectionOfAFrame) {
  Params p;
  p.threshold.moving_threshold_scale = 0.1;
  p.orb.moving_noise_floor = 5.0;
  // auto: the judgment decides.
  EXPECT_FALSE(p.movingSelection(false));
  EXPECT_TRUE(p.movingSelection(true));
  EXPECT_DOUBLE_EQ(p.forFrame(false).threshold.threshold_scale, 0.3);
  EXPECT_DOUBLE_EQ(p.forFrame(false).orb.noise_floor, 0.0);
  EXPECT_DOUBLE_EQ(p.forFrame(true).threshold.threshold_scale, 0.1);
  EXPECT_DOUBLE_EQ(p.forFrame(true).orb.noise_floor, 5.0);
  EXPECT_EQ(p.forFrame(false).enhance.gamma_mode, GammaMode::kAlways);
  EXPECT_EQ(p.forFrame(true).enhance.gamma_mode, GammaMode::kNever);  // moving_gamma_mode
  // With the stream's lambda, moving_gamma_mode auto is decided on it; a still frame ignores it.
  p.enhance.moving_gamma_mode = GammaMode::kAuto;
  EXPECT_EQ(p.forFrame(true).enhance.gamma_mode, GammaMode::kAuto);
  EXPECT_EQ(p.forFrame(true, 0.26).enhance.gamma_mode, GammaMode::kAlways);
  EXPECT_EQ(p.forFrame(true, 0.25).enhance.gamma_mode, GammaMode::kNever);  // not above std_threshold
  EXPECT_EQ(p.forFrame(true, 0.0).enhance.gamma_mode, GammaMode::kNever);
  EXPECT_EQ(p.forFrame(false, 0.1).enhance.gamma_mode, GammaMode::kAlways);
  p.enhance.std_threshold = 0.1;
  EXPECT_EQ(p.forFrame(true, 0.2).enhance.gamma_mode, GammaMode::kAlways);
  p.enhance.std_threshold = 0.25;
  p.enhance.moving_gamma_mode = GammaMode::kNever;
  EXPECT_EQ(p.forFrame(true, 0.9).enhance.gamma_mode, GammaMode::kNever);
  p.enhance.moving_gamma_mode = GammaMode::kAuto;
  // Who judges a stream: the default mode's extraction and enhancement (a moving camera's frames
  // get no curve, a still one's do), the motion preset's enhancement only with moving_gamma_mode
  // auto (its frames' lambda), neither for a still camera or the paper.
  EXPECT_TRUE(Params().judgesStream());
  EXPECT_TRUE(Params().enhancementJudgesStream());
  EXPECT_FALSE(Params::motion().judgesStream());  // the moving selection and no curve, whatever comes
  Params motion_tested = Params::motion();
  motion_tested.enhance.moving_gamma_mode = GammaMode::kAuto;
  EXPECT_TRUE(motion_tested.judgesStream());
  EXPECT_TRUE(motion_tested.enhancementJudgesStream());
  EXPECT_FALSE(Params::paper().judgesStream());
  EXPECT_FALSE(Params::baseline().judgesStream());
  Params fixed_curve = Params::motion();
  fixed_curve.enhance.moving_gamma_mode = GammaMode::kNever;
  EXPECT_FALSE(fixed_curve.judgesStream());
  fixed_curve.orb.camera_motion = MotionMode::kAuto;
  EXPECT_TRUE(fixed_curve.judgesStream());             // the selection
  EXPECT_TRUE(fixed_curve.enhancementJudgesStream());  // never while moving, always while still
  fixed_curve.enhance.gamma_mode = GammaMode::kNever;
  EXPECT_FALSE(fixed_curve.enhancementJudgesStream());  // the same curve either way
  fixed_curve.enhance_enabled = false;
  fixed_curve.enhance.moving_gamma_mode = GammaMode::kAuto;
  EXPECT_FALSE(fixed_curve.enhancementJudgesStream());
  // still and moving: the judgment is not read.
  p.orb.camera_motion = MotionMode::kStill;
  EXPECT_FALSE(p.movingSelection(true));
  EXPECT_DOUBLE_EQ(p.forFrame(true).orb.noise_floor, 0.0);
  p.orb.camera_motion = MotionMode::kMoving;
  EXPECT_TRUE(p.movingSelection(false));
  EXPECT_DOUBLE_EQ(p.forFrame(false).orb.noise_floor, 5.0);
  // Everything else is the same in both selections.
  Params moving = p.forFrame(true);
  moving.threshold.threshold_scale = p.threshold.threshold_scale;
  moving.orb.noise_floor = p.orb.noise_floor;
  moving.enhance.gamma_mode = p.enhance.gamma_mode;
  EXPECT_EQ(asText(moving), asText(p));
  // By name, as the nodelets and tools set it.
  EXPECT_EQ(setParam(p, "camera_motion", "auto"), "");
  EXPECT_EQ(p.orb.camera_motion, MotionMode::kAuto);
  EXPECT_EQ(setParam(p, "camera_motion", "walking"), "camera_motion 'walking' is not auto|still|moving");
  EXPECT_EQ(p.orb.camera_motion, MotionMode::kAuto);
  // The presets that are the paper's or keep the strongest corners never switch.
  EXPECT_EQ(Params::paper().orb.camera_motion, MotionMode::kStill);
  EXPECT_EQ(Params::baseline().orb.camera_motion, MotionMode::kStill);
  EXPECT_EQ(Params::stretch().orb.camera_motion, MotionMode::kStill);
}

TEST(ParamTable, EveryParameterOnceWithTheDefaultModesValueAndItsRange) {
  const std::vector<ParamInfo> table = paramTable();
  std::vector<std::string> names;
  for (const ParamInfo& row : table) {
    names.push_back(row.name);
    EXPECT_FALSE(row.meaning.empty()) << row.name;
  }
  EXPECT_EQ(names, paramNames());
  for (const ParamInfo& row : table) {
    // The default shown is the default mode's value.
    Params p;
    ASSERT_EQ(setParam(p, row.name, row.default_text), "") << row.name;
    EXPECT_EQ(asText(p), asText(Params())) << row.name << " default " << row.default_text;
    if (!row.has_range) {
      continue;
    }
    // validate() accepts the range's ends and refuses what lies just outside it.
    const double step = row.type == "int" ? 1.0 : 1e-6;
    auto accepted = [&](double v) {
      Params q;
      std::ostringstream text;
      text.precision(17);
      text << (row.type == "int" ? std::round(v) : v);
      EXPECT_EQ(setParam(q, row.name, text.str()), "") << row.name << " " << text.str();
      return validate(q).empty();
    };
    EXPECT_TRUE(accepted(row.lo)) << row.name;
    EXPECT_TRUE(accepted(row.hi)) << row.name;
    EXPECT_FALSE(accepted(row.lo - step)) << row.name;
    EXPECT_FALSE(accepted(row.hi + step)) << row.name;
  }
}

TEST(ParamTable, UsageListsEveryParameterAsAnOption) {
  const std::string usage = paramUsage();
  for (std::string name : paramNames()) {
    std::replace(name.begin(), name.end(), '_', '-');
    EXPECT_NE(usage.find("--" + name + " "), std::string::npos) << name;
  }
  EXPECT_NE(usage.find("--alpha X in [0, 1] (default 0.5)"), std::string::npos) << usage;
}

TEST(Presets, BaselineIsAPresetLikeTheOthers) {
  Preset parsed = Preset::kDefault;
  ASSERT_TRUE(parsePreset("baseline", parsed));
  EXPECT_EQ(parsed, Preset::kBaseline);
  EXPECT_EQ(asText(Params::preset(Preset::kBaseline)), asText(Params::baseline()));
  const Params b = Params::preset(Preset::kBaseline);
  EXPECT_FALSE(b.enhance_enabled);
  EXPECT_EQ(b.orb.threshold_mode, ThresholdMode::kFixed);
  EXPECT_EQ(b.orb.fast_threshold, 20);
  EXPECT_NE(presetNames().find("baseline"), std::string::npos);
}
