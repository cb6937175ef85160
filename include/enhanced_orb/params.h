// Parameters of the method: the default mode's values, the `paper` preset, range checks.
//
// Dai & Wu, "An Improved ORB Feature Extraction Algorithm Based on Enhanced Image and Truncated
// Adaptive Threshold", IEEE Access 11 (2023). Names follow the ROS parameter names.
//
// The member initialisers below are the default mode: the paper's parts (histogram-driven tone
// curve, Gaussian filter, truncated adaptive threshold, ORB), set for a fixed feature budget under
// real lighting change (docs/RESULTS.md has the measurements behind each choice). Params::paper()
// is the method exactly as published; Params::baseline() the original ORB it is compared with.
#ifndef ENHANCED_ORB_PARAMS_H
#define ENHANCED_ORB_PARAMS_H

#include <optional>
#include <string>
#include <vector>

namespace enhanced_orb {

// When to apply the truncated adaptive gamma (step 3 of section III-A).
enum class GammaMode {
  kAuto,    // the paper's quality test: poor when lambda > std_threshold
  kAlways,  // treat every image as poor quality
  kNever,   // never apply the gamma correction (filter and unsharp mask only)
};

// The histogram-driven tone curve LUT of eqs 10-17.
enum class ToneCurve {
  kGamma,     // the paper's truncated adaptive gamma, eqs 14-16 (on the plain histogram)
  kEqualize,  // edge-weighted equalisation: each pixel counts by sqrt(|gradient|), one global curve
  kStretch,   // linear stretch of the tones between the tau and 1 - tau quantiles (the raw tone order)
};

// Named parameter sets.
enum class Preset {
  kDefault,   // the default mode (the member initialisers)
  kPaper,     // Dai & Wu's method as published (ALGORITHM.md)
  kStretch,   // the default mode with the raw tone order: well-exposed scenes whose light changes locally
  kMotion,    // the default mode with camera_motion moving: the moving camera's selection from the first frame
  kBaseline,  // the paper's original ORB: no enhancement, FAST 20 everywhere (Params::baseline())
};

// Which selection a frame gets: the still camera's (threshold_scale, noise_floor) or the moving
// camera's (moving_threshold_scale, moving_noise_floor).
enum class MotionMode {
  kAuto,    // judged per stream from the frames in order (camera_motion.h); single images: still
  kStill,   // always the still camera's
  kMoving,  // always the moving camera's
};

// How the FAST threshold of each grid cell is chosen.
enum class ThresholdMode {
  kAdaptive,  // truncated adaptive threshold, eqs 33-34
  kFixed,     // one threshold everywhere (the original ORB)
};

// Section III-A: image enhancement.
struct EnhanceParams {
  ToneCurve tone_curve = ToneCurve::kEqualize;
  double alpha = 0.5;  // eq 12: smoothness exponent of the weighted histogram, [0, 1]
  // eq 15 (gamma: lower truncation of gamma_i; equalize: least slope; stretch: the fraction of pixels
  // clipped at each end, below 0.5), [0, 1]
  double tau = 0.0;
  double beta = 1.0;            // eq 20: weight of the brightness mask T_mask, [0, 2]
  double sharpening = -1.0;     // eq 19: unsharp-mask degree, [-1, 5]; -1 leaves the filtered image f
  int blur_ksize = 3;           // eq 8: Gaussian kernel size, odd, [1, 31]
  double blur_sigma = 1.0;      // eq 8: Gaussian sigma, [0.1, 10]
  double std_threshold = 0.25;  // step 3: quality test on lambda (gamma_mode or moving_gamma_mode auto), [0, 1]
  GammaMode gamma_mode = GammaMode::kAlways;
  // gamma_mode while the camera moves (OrbParams::camera_motion): a moving camera's consecutive
  // frames share their exposure, so their descriptors need no tone normalisation, and on a dim
  // frame the curve mostly stretches the noise of the dark tones; never, since relative pose from
  // the median of five RANSAC draws gains without it in good light on a car and in fading light
  // indoors (docs/RESULTS.md, "A moving camera's tone curve"). auto tests the stream's recent
  // frames, not each frame alone (CameraMotion::kToneFrames). The ORB-SLAM adapter takes always
  // unless its file sets this (orb_slam_extractor.h).
  GammaMode moving_gamma_mode = GammaMode::kNever;
  // Threads one enhancement uses (horizontal bands, through cv::parallel_for_); the result is the
  // same for any count. [1, 64]
  int threads = 1;
};

// Section III-B: truncated adaptive threshold.
struct ThresholdParams {
  int grid_size = 5;             // m: the image is cut into m x m cells, [1, 32]
  double threshold_scale = 0.3;  // a, eq 33, [0, 2]
  // a while the camera moves (OrbParams::camera_motion): every cell at c_min, so that corners are
  // found over the whole view. [0, 2]
  double moving_threshold_scale = 0.0;
  int c_min = 7;  // C_min, eq 34, [1, 200]
};

// Section II and IV: the ORB pipeline around the threshold.
struct OrbParams {
  ThresholdMode threshold_mode = ThresholdMode::kAdaptive;
  int fast_threshold = 20;  // the original ORB's fixed threshold (kFixed), [1, 200]
  int max_features = 1000;  // 0: every corner; > 0: budget over all levels, [0, 100000]
  // > 0: a level's spread selection draws from its candidate_ratio x budget strongest corners only;
  // 0: from every corner (the paper). [0, 100]
  double candidate_ratio = 1.5;
  // > 0: at a budget, a level's spread selection draws from its corners whose FAST score is at
  // least noise_floor x the frame's noise (estimateNoise() of the image the corners are found on),
  // and at least from its budget's strongest (at most floor_candidate_ratio x budget of them);
  // candidate_ratio is then not used. 0: off. [0, 50]
  double noise_floor = 0.0;
  // noise_floor while the camera moves: the budget spread over every corner that stands out of the
  // noise, for relative pose and tracking (docs/RESULTS.md, "Real camera motion"). [0, 50]
  double moving_noise_floor = 8.0;
  // > 0: of a level's corners above the noise floor in use (noise_floor, or moving_noise_floor while
  // the camera moves), the spread draws from at most its floor_candidate_ratio x budget strongest,
  // so that at a small budget in good light the weakest corners above the noise are left out; 16,
  // since relative pose from five RANSAC draws gains with it at 500 features in good light and
  // hardly changes at 1000 and 2000 or in noisy light, where it seldom binds (docs/RESULTS.md,
  // "Real camera motion"). 0: from every corner above the floor. [0, 100]
  double floor_candidate_ratio = 16.0;
  // Which of the two selections a frame gets; auto judges from a stream's frames whether its
  // camera moves (CameraMotion, ExtractOptions::camera_moving).
  MotionMode camera_motion = MotionMode::kAuto;
  int n_levels = 8;           // pyramid levels, [1, 16]
  double scale_factor = 1.2;  // pyramid scale between levels, [1.01, 2]
  // Threads one extraction's pyramid levels use, through cv::parallel_for_ (OpenCV's pool,
  // cv::setNumThreads, bounds it); the results are the same for any count. The enhancement's
  // threads are EnhanceParams::threads. [1, 64]
  int threads = 1;
};

// Everything one extraction needs.
struct Params {
  bool enhance_enabled = true;  // false: the input is used as it is (already enhanced, or baseline)
  EnhanceParams enhance;
  ThresholdParams threshold;
  OrbParams orb;

  // Dai & Wu's method as published: ALGORITHM.md, every corner kept.
  static Params paper();
  // The paper's "original ORB": the paper preset with no enhancement and one fixed threshold.
  static Params baseline(int fast_threshold = 20);
  // The default mode with tone_curve stretch (tau 0.05) and candidate_ratio 1: a frame's tones are
  // only stretched linearly and each level keeps its strongest corners, so the ranking is the
  // camera's own. For well-exposed scenes whose light changes inside the frame (sun and shadow).
  static Params stretch();
  // The default mode with camera_motion moving: every frame gets the moving camera's selection,
  // from the first one on.
  static Params motion();
  static Params preset(Preset preset);

  // Whether a frame gets the moving camera's selection: camera_motion moving, or auto and the
  // frame's camera judged moving.
  bool movingSelection(bool judged_moving) const;
  // The parameters a frame is enhanced and extracted with: these, with gamma_mode,
  // threshold_scale and noise_floor the moving_ ones where movingSelection(judged_moving). With
  // moving_gamma_mode auto, a moving camera's frame is tested on `stream_lambda` where it is >= 0
  // (CameraMotion::streamLambda(): the stream's recent frames, so that they are enhanced alike)
  // instead of on its own lambda: gamma_mode becomes always or never.
  Params forFrame(bool judged_moving, double stream_lambda = -1.0) const;
  // Whether a frame's enhancement depends on its stream (CameraMotion: the judgment, or the stream's
  // lambda for moving_gamma_mode auto), and whether its extraction does (the enhancement's, or the
  // selection under camera_motion auto): a caller that feeds a stream then judges its frames.
  bool enhancementJudgesStream() const;
  bool judgesStream() const;
};

// Range checks. Each returns one message per offending value, naming the parameter, the value and
// the allowed range ("alpha = 1.5 is out of range [0, 1]"); empty when everything is valid.
std::vector<std::string> validate(const EnhanceParams& p);
std::vector<std::string> validate(const ThresholdParams& p);
std::vector<std::string> validate(const OrbParams& p);
std::vector<std::string> validate(const Params& p);

// Sets one parameter by its ROS name from text, e.g. ("alpha", "0.5"), ("tone_curve", "gamma"),
// ("enhance", "false"). Returns an error naming the parameter and the value when the name is
// unknown, or "<name> '<text>' is not <what it takes>" when the text is not a whole value of the
// parameter's type; empty on success. Ranges are checked by validate().
std::string setParam(Params& params, const std::string& name, const std::string& value);

// Every name setParam() knows, in one fixed order.
std::vector<std::string> paramNames();

// The value of the parameter `name` as text that setParam() reads back to the same value; nullopt
// for a name setParam() does not know.
std::optional<std::string> paramText(const Params& params, const std::string& name);

// One row of the parameter table behind setParam(), paramText(), validate()'s range checks and the
// tools' usage text: the ROS name, the type ("bool", "int", "double", or the names an enum reads:
// "auto|always|never"), the range for numbers, the default mode's value and the meaning.
struct ParamInfo {
  std::string name;
  std::string type;
  bool has_range = false;
  double lo = 0.0, hi = 0.0;
  std::string default_text;
  std::string meaning;
};
std::vector<ParamInfo> paramTable();

// The table as command-line options, two lines each: "  --alpha X in [0, 1] (default 0.5)", then
// the meaning.
std::string paramUsage();

// The parameters that have no effect under `params`, each with the reason ("std_threshold: only
// used when gamma_mode is auto"), so that a tool or nodelet can say so when one of them is set.
std::vector<std::string> inactiveParameters(const Params& params);

// Joins validation messages into one line, for logs and exceptions.
std::string joinMessages(const std::vector<std::string>& messages);

// Name <-> enum for command lines, launch files and YAML ("auto", "always", "never";
// "adaptive", "fixed"). parse* return false on an unknown name and leave `out` unchanged.
const char* toString(GammaMode mode);
const char* toString(ThresholdMode mode);
const char* toString(ToneCurve curve);
const char* toString(Preset preset);
const char* toString(MotionMode mode);
bool parseMotionMode(const std::string& name, MotionMode& out);  // "auto", "still", "moving"
bool parseGammaMode(const std::string& name, GammaMode& out);
bool parseThresholdMode(const std::string& name, ThresholdMode& out);
bool parseToneCurve(const std::string& name, ToneCurve& out);  // "gamma", "equalize", "stretch"
bool parsePreset(const std::string& name, Preset& out);        // "default", "paper", "stretch", "motion", "baseline"
// The names each parser reads, for messages: "default, paper or stretch".
std::string toneCurveNames();
std::string presetNames();
std::string gammaModeNames();
std::string thresholdModeNames();
std::string motionModeNames();

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_PARAMS_H
