// enhanced_orb_extract: runs the extractor on image files and writes one YAML file per image.
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <functional>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "enhanced_orb/draw.h"
#include "enhanced_orb/orb_extractor.h"

namespace fs = std::filesystem;
using enhanced_orb::Extraction;
using enhanced_orb::Params;

namespace {

const char* const kUsage = R"(usage: enhanced_orb_extract [options] IMAGE... --output DIR

Runs the enhanced ORB extractor on each IMAGE (any format OpenCV reads; colour is turned to gray)
and writes DIR/<stem>.yml (cv::FileStorage) with keypoints (N x 6 float: x, y, size, angle,
response, octave), descriptors (N x 32 uint8), thresholds (grid x grid int, level 0), lambda,
poor_quality, inverted, enhance_ms and extract_ms.

options:
  --output DIR           where to write (created if missing; required)
  --baseline             the original ORB: no enhancement, fixed threshold (--fast-threshold)
  --no-enhance           skip the enhancement, keep the adaptive threshold
  --max-features N       0 = every corner (default), > 0 = budget over all levels
  --alpha X  --tau X  --beta X  --sharpening X     enhancement (paper defaults 0.2 0.3 0.3 1.0)
  --gamma-mode auto|always|never                    quality test (default auto)
  --grid-size N  --threshold-scale X  --c-min N     adaptive threshold (defaults 5 0.3 7)
  --fast-threshold N     fixed threshold of the baseline (default 20)
  --n-levels N  --scale-factor X                   pyramid (defaults 8 1.2)
  --save-enhanced        also write DIR/<stem>_enhanced.png
  --save-annotated       also write DIR/<stem>_annotated.png
  -h, --help             this text
)";

struct Options {
  Params params;
  bool baseline = false;
  bool no_enhance = false;
  bool save_enhanced = false;
  bool save_annotated = false;
  std::string output;
  std::vector<std::string> images;
};

// Strict number parsing: the whole argument must be a number.
template <typename T>
bool parseNumber(const std::string& text, T& out) {
  std::istringstream in(text);
  T value{};
  in >> value;
  if (in.fail() || !in.eof()) {
    return false;
  }
  out = value;
  return true;
}

// Returns an error message, empty on success.
std::string parseArguments(int argc, char** argv, Options& opt) {
  Params& p = opt.params;
  const std::map<std::string, std::function<bool(const std::string&)>> valued = {
      {"--output", [&](const std::string& v) { return !(opt.output = v).empty(); }},
      {"--max-features", [&](const std::string& v) { return parseNumber(v, p.orb.max_features); }},
      {"--alpha", [&](const std::string& v) { return parseNumber(v, p.enhance.alpha); }},
      {"--tau", [&](const std::string& v) { return parseNumber(v, p.enhance.tau); }},
      {"--beta", [&](const std::string& v) { return parseNumber(v, p.enhance.beta); }},
      {"--sharpening", [&](const std::string& v) { return parseNumber(v, p.enhance.sharpening); }},
      {"--gamma-mode", [&](const std::string& v) { return enhanced_orb::parseGammaMode(v, p.enhance.gamma_mode); }},
      {"--grid-size", [&](const std::string& v) { return parseNumber(v, p.threshold.grid_size); }},
      {"--threshold-scale", [&](const std::string& v) { return parseNumber(v, p.threshold.threshold_scale); }},
      {"--c-min", [&](const std::string& v) { return parseNumber(v, p.threshold.c_min); }},
      {"--fast-threshold", [&](const std::string& v) { return parseNumber(v, p.orb.fast_threshold); }},
      {"--n-levels", [&](const std::string& v) { return parseNumber(v, p.orb.n_levels); }},
      {"--scale-factor", [&](const std::string& v) { return parseNumber(v, p.orb.scale_factor); }},
  };
  const std::map<std::string, bool*> flags = {{"--baseline", &opt.baseline},
                                              {"--no-enhance", &opt.no_enhance},
                                              {"--save-enhanced", &opt.save_enhanced},
                                              {"--save-annotated", &opt.save_annotated}};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (auto flag = flags.find(arg); flag != flags.end()) {
      *flag->second = true;
    } else if (auto option = valued.find(arg); option != valued.end()) {
      if (i + 1 >= argc) {
        return arg + " needs a value";
      }
      const std::string value = argv[++i];
      if (!option->second(value)) {
        return "invalid value for " + arg + ": '" + value + "'";
      }
    } else if (arg.size() > 1 && arg[0] == '-') {
      return "unknown option " + arg;
    } else {
      opt.images.push_back(arg);
    }
  }
  if (opt.output.empty()) {
    return "--output DIR is required";
  }
  if (opt.images.empty()) {
    return "no IMAGE given";
  }
  if (opt.baseline) {
    p.enhance_enabled = false;
    p.orb.threshold_mode = enhanced_orb::ThresholdMode::kFixed;
  }
  if (opt.no_enhance) {
    p.enhance_enabled = false;
  }
  const std::vector<std::string> problems = enhanced_orb::validate(p);
  return problems.empty() ? "" : enhanced_orb::joinMessages(problems);
}

cv::Mat keypointMatrix(const std::vector<cv::KeyPoint>& keypoints) {
  cv::Mat m(static_cast<int>(keypoints.size()), 6, CV_32F);
  for (int i = 0; i < m.rows; ++i) {
    const cv::KeyPoint& kp = keypoints[i];
    float* row = m.ptr<float>(i);
    row[0] = kp.pt.x;
    row[1] = kp.pt.y;
    row[2] = kp.size;
    row[3] = kp.angle;
    row[4] = kp.response;
    row[5] = static_cast<float>(kp.octave);
  }
  return m;
}

void writeResult(const fs::path& file, const Extraction& r) {
  cv::FileStorage fs(file.string(), cv::FileStorage::WRITE);
  if (!fs.isOpened()) {
    throw std::runtime_error("cannot write " + file.string());
  }
  fs << "keypoints" << keypointMatrix(r.keypoints);
  fs << "descriptors" << r.descriptors;
  fs << "thresholds" << r.cell_thresholds;
  fs << "lambda" << r.lambda;
  fs << "poor_quality" << static_cast<int>(r.poor_quality);
  fs << "inverted" << static_cast<int>(r.inverted);
  fs << "enhance_ms" << r.timings.enhance_ms;
  fs << "extract_ms" << r.timings.extractMs();
}

void writeImage(const fs::path& file, const cv::Mat& image) {
  if (!cv::imwrite(file.string(), image)) {
    throw std::runtime_error("cannot write " + file.string());
  }
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "-h" || std::string(argv[i]) == "--help") {
      std::cout << kUsage;
      return 0;
    }
  }
  Options opt;
  const std::string error = parseArguments(argc, argv, opt);
  if (!error.empty()) {
    std::cerr << "enhanced_orb_extract: " << error << "\n\n" << kUsage;
    return 2;
  }
  try {
    fs::create_directories(opt.output);
    const enhanced_orb::OrbExtractor extractor(opt.params);
    int failures = 0;
    for (const std::string& path : opt.images) {
      const cv::Mat gray = cv::imread(path, cv::IMREAD_GRAYSCALE);
      if (gray.empty()) {
        std::cerr << "enhanced_orb_extract: cannot read image '" << path << "'\n";
        ++failures;
        continue;
      }
      const Extraction r = extractor.extract(gray);
      const fs::path stem = fs::path(opt.output) / fs::path(path).stem();
      writeResult(stem.string() + ".yml", r);
      if (opt.save_enhanced) {
        writeImage(stem.string() + "_enhanced.png", r.image);
      }
      if (opt.save_annotated) {
        std::ostringstream caption;
        caption << r.keypoints.size() << " keypoints, " << cvRound(r.timings.totalMs() * 10) / 10.0 << " ms";
        writeImage(
            stem.string() + "_annotated.png",
            enhanced_orb::drawAnnotated(r.image, r.keypoints, r.cell_thresholds, caption.str(), {true, true, true}));
      }
      std::cout << path << ": " << r.keypoints.size() << " keypoints, enhance " << r.timings.enhance_ms
                << " ms, extract " << r.timings.extractMs() << " ms\n";
    }
    return failures == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "enhanced_orb_extract: " << e.what() << "\n";
    return 1;
  }
}
