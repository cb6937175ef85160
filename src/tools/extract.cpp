// enhanced_orb_extract: runs the extractor on image files and writes one YAML file per image.
#include <algorithm>
#include <cstdlib>
#include <exception>
#include <filesystem>
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
  --preset NAME          default (the default mode, 1000 features) or paper (Dai & Wu as
                         published, every corner); parameters given after it override it
  --baseline             the original ORB: the paper preset without enhancement, fixed threshold
  --no-enhance           skip the enhancement, keep the adaptive threshold
  --save-enhanced        also write DIR/<stem>_enhanced.png
  --save-annotated       also write DIR/<stem>_annotated.png
  -h, --help             this text
parameters (README "Parameters" gives each one's meaning, default and range):
  --max-features N  --candidate-ratio X  --n-levels N  --scale-factor X
  --tone-curve equalize|gamma  --tone-tiles N  --alpha X  --tau X  --beta X  --sharpening X
  --blur-ksize N  --blur-sigma X  --gamma-mode auto|always|never  --std-threshold X
  --grid-size N  --threshold-scale X  --c-min N  --threshold-mode adaptive|fixed  --fast-threshold N
A value must be a whole number of the parameter's type and lie in its range; when an option is
repeated, the last one wins.
exit codes: 0 every image done, 1 an image could not be read or written, 2 bad arguments.
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

// Returns an error message, empty on success.
std::string parseArguments(int argc, char** argv, Options& opt) {
  // The preset first, wherever it stands: the other options adjust it.
  enhanced_orb::Preset preset = enhanced_orb::Preset::kDefault;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--preset" && !enhanced_orb::parsePreset(argv[i + 1], preset)) {
      return std::string("invalid value for --preset: '") + argv[i + 1] + "' (default or paper)";
    }
  }
  Params& p = opt.params;
  p = Params::preset(preset);
  const std::map<std::string, bool*> flags = {{"--baseline", &opt.baseline},
                                              {"--no-enhance", &opt.no_enhance},
                                              {"--save-enhanced", &opt.save_enhanced},
                                              {"--save-annotated", &opt.save_annotated}};
  std::vector<std::pair<std::string, std::string>> settings;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (auto flag = flags.find(arg); flag != flags.end()) {
      *flag->second = true;
    } else if (arg.rfind("--", 0) == 0) {
      if (i + 1 >= argc) {
        return arg + " needs a value";
      }
      const std::string value = argv[++i];
      if (arg == "--output") {
        opt.output = value;
      } else if (arg != "--preset") {
        std::string name = arg.substr(2);
        std::replace(name.begin(), name.end(), '-', '_');
        if (name == "enhance") {
          return "unknown option " + arg;
        }
        settings.emplace_back(name, value);
      }
    } else if (arg.size() > 1 && arg[0] == '-') {
      return "unknown option " + arg;
    } else {
      opt.images.push_back(arg);
    }
  }
  if (opt.baseline) {
    p = Params::baseline();
  }
  for (const auto& [name, value] : settings) {
    const std::string error = enhanced_orb::setParam(p, name, value);
    if (!error.empty()) {
      return error.rfind("unknown parameter", 0) == 0 ? "unknown option --" + name : error;
    }
  }
  if (opt.output.empty()) {
    return "--output DIR is required";
  }
  if (opt.images.empty()) {
    return "no IMAGE given";
  }
  if (opt.no_enhance) {
    p.enhance_enabled = false;
  }
  for (const std::string& inactive : enhanced_orb::inactiveParameters(p)) {
    for (const auto& setting : settings) {
      if (inactive.rfind(setting.first + ":", 0) == 0) {
        std::cerr << "enhanced_orb_extract: warning: --" << setting.first << " has no effect here (" << inactive
                  << ")\n";
      }
    }
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
        writeImage(stem.string() + "_annotated.png",
                   enhanced_orb::drawAnnotated(r.image, r.keypoints, r.cell_thresholds, caption.str(),
                                               enhanced_orb::DrawOptions{true, false, true, true, 300}));
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
