// Parameters of the method, with the paper's defaults and range checks.
//
// Dai & Wu, "An Improved ORB Feature Extraction Algorithm Based on Enhanced Image and Truncated
// Adaptive Threshold", IEEE Access 11 (2023). Names follow the ROS parameter names.
#ifndef ENHANCED_ORB_PARAMS_H
#define ENHANCED_ORB_PARAMS_H

#include <string>
#include <vector>

namespace enhanced_orb {

// When to apply the truncated adaptive gamma (step 3 of section III-A).
enum class GammaMode {
  kAuto,    // the paper's quality test: poor when lambda > std_threshold
  kAlways,  // treat every image as poor quality
  kNever,   // never apply the gamma correction (filter and unsharp mask only)
};

// How the FAST threshold of each grid cell is chosen.
enum class ThresholdMode {
  kAdaptive,  // truncated adaptive threshold, eqs 33-34
  kFixed,     // one threshold everywhere (the original ORB)
};

// Section III-A: image enhancement.
struct EnhanceParams {
  double alpha = 0.2;           // eq 12: smoothness exponent of the weighted histogram, [0, 1]
  double tau = 0.3;             // eq 15: lower truncation of the per-level gamma, [0, 1]
  double beta = 0.3;            // eq 20: weight of the brightness mask T_mask, [0, 2]
  double sharpening = 1.0;      // eq 19: unsharp-mask degree, [0, 5]
  int blur_ksize = 5;           // eq 8: Gaussian kernel size, odd, [1, 31]
  double blur_sigma = 1.0;      // eq 8: Gaussian sigma, [0.1, 10]
  double std_threshold = 0.25;  // step 3: quality test on lambda, [0, 1]
  GammaMode gamma_mode = GammaMode::kAuto;
};

// Section III-B: truncated adaptive threshold.
struct ThresholdParams {
  int grid_size = 5;             // m: the image is cut into m x m cells, [1, 32]
  double threshold_scale = 0.3;  // a, eq 33, [0, 2]
  int c_min = 7;                 // C_min, eq 34, [1, 200]
};

// Section II and IV: the ORB pipeline around the threshold.
struct OrbParams {
  ThresholdMode threshold_mode = ThresholdMode::kAdaptive;
  int fast_threshold = 20;    // the original ORB's fixed threshold (kFixed), [1, 200]
  int max_features = 0;       // 0: every corner; > 0: budget over all levels, [0, 100000]
  int n_levels = 8;           // pyramid levels, [1, 16]
  double scale_factor = 1.2;  // pyramid scale between levels, [1.01, 2]
};

// Everything one extraction needs.
struct Params {
  bool enhance_enabled = true;  // false: the input is used as it is (already enhanced, or baseline)
  EnhanceParams enhance;
  ThresholdParams threshold;
  OrbParams orb;

  // The paper's "original ORB": no enhancement, one fixed threshold, everything else identical.
  static Params baseline(int fast_threshold = 20);
};

// Range checks. Each returns one message per offending value, naming the parameter, the value and
// the allowed range ("alpha = 1.5 is out of range [0, 1]"); empty when everything is valid.
std::vector<std::string> validate(const EnhanceParams& p);
std::vector<std::string> validate(const ThresholdParams& p);
std::vector<std::string> validate(const OrbParams& p);
std::vector<std::string> validate(const Params& p);

// Joins validation messages into one line, for logs and exceptions.
std::string joinMessages(const std::vector<std::string>& messages);

// Name <-> enum for command lines, launch files and YAML ("auto", "always", "never";
// "adaptive", "fixed"). parse* return false on an unknown name and leave `out` unchanged.
const char* toString(GammaMode mode);
const char* toString(ThresholdMode mode);
bool parseGammaMode(const std::string& name, GammaMode& out);
bool parseThresholdMode(const std::string& name, ThresholdMode& out);

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_PARAMS_H
