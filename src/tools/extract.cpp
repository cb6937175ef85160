// enhanced_orb_extract: runs the extractor on image files and writes one YAML file per image.
#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/draw.h"
#include "enhanced_orb/evaluation/files.h"
#include "enhanced_orb/orb_extractor.h"

namespace fs = std::filesystem;
using enhanced_orb::Extraction;
using enhanced_orb::Params;

namespace {

const char* const kUsage = R"(usage: enhanced_orb_extract [options] IMAGE... --output DIR

Runs the enhanced ORB extractor on each IMAGE (any format OpenCV reads; colour is turned to gray)
and writes DIR/<stem>.yml (cv::FileStorage; DIR/<folder>/<stem>.yml when names repeat in several
folders) with keypoints (N x 6 float: x, y, size, angle, response, octave), descriptors (N x 32
uint8), thresholds (grid x grid int, level 0), lambda, poor_quality, inverted, camera_moving,
judge_ms (the camera-motion judgment), enhance_ms, extract_ms and total_ms (the whole call on the
gray image: the three, less the time the judgment and the enhancement ran side by side with
--threads 2 or more). The IMAGEs are taken as one
camera's frames in the order given: with --camera-motion auto (the default) they decide whether the
camera is judged moving. An image unrelated to the one before it (another scene) is not motion: it
is reported as a new scene and the judgment stays as it was, so a folder of unrelated scenes, each
shot from one place, is judged still throughout. --camera-motion still skips the judgment.

options:
  --output DIR           where to write (created if missing; required)
  --preset NAME          the parameters to start from: default, motion, stretch, paper or
                         baseline (README "Which mode to use"); the parameters given override it
  --save-enhanced        also write DIR/<stem>_enhanced.png
  --save-annotated       also write DIR/<stem>_annotated.png
  --time-opencv          also time cv::ORB (same budget, 8 levels, 1.2; every corner when the budget
                         is 0) on each image, and end with the means and their ratio
  --max-pixels N         refuse images larger than N pixels (default 33554432 = 32 Mpixel, as the
                         nodelets), read from the file header before decoding where the format allows
  -h, --help             this text
parameters (README "Parameters"), each --name VALUE; the defaults are the default mode's:
%PARAMETERS%
A value must be a whole number of the parameter's type and lie in its range; when an option is
repeated, the last one wins.
Outputs never collide: two images with the same stem (a/x.png, b/x.png) are refused before
anything is written, as is an output that would overwrite an input. Each file is written under a
temporary name and renamed when complete. An image that cannot be read, or is too large, is
reported and skipped; the others are processed.
exit codes: 0 every image done, 1 an image was skipped or an output could not be written,
2 bad arguments (nothing written).
)";

// The usage text with the parameter table's options in place of %PARAMETERS%.
std::string usage() {
  std::string text = kUsage;
  const std::string marker = "%PARAMETERS%";
  text.replace(text.find(marker), marker.size(), enhanced_orb::paramUsage());
  return text;
}

struct Options {
  Params params;
  bool save_enhanced = false;
  bool save_annotated = false;
  bool time_opencv = false;
  long long max_pixels = enhanced_orb::kMaxImagePixels;
  std::string output;
  std::vector<std::string> images;
};

// Returns an error message, empty on success.
std::string parseArguments(int argc, char** argv, Options& opt) {
  // The preset first, wherever it stands: the other options adjust it.
  enhanced_orb::Preset preset = enhanced_orb::Preset::kDefault;
  for (int i = 1; i + 1 < argc; ++i) {
    if (std::string(argv[i]) == "--preset" && !enhanced_orb::parsePreset(argv[i + 1], preset)) {
      return std::string("invalid value for --preset: '") + argv[i + 1] + "' (" + enhanced_orb::presetNames() + ")";
    }
  }
  Params& p = opt.params;
  p = Params::preset(preset);
  const std::map<std::string, bool*> flags = {{"--save-enhanced", &opt.save_enhanced},
                                              {"--save-annotated", &opt.save_annotated},
                                              {"--time-opencv", &opt.time_opencv}};
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
      } else if (arg == "--max-pixels") {
        std::istringstream in(value);
        long long n = 0;
        in >> n;
        if (in.fail() || !in.eof() || n < 1) {
          return "invalid value for --max-pixels: '" + value + "' (a positive whole number)";
        }
        opt.max_pixels = n;
      } else if (arg != "--preset") {
        std::string name = arg.substr(2);
        std::replace(name.begin(), name.end(), '-', '_');
        settings.emplace_back(name, value);
      }
    } else if (arg.size() > 1 && arg[0] == '-') {
      return "unknown option " + arg;
    } else {
      opt.images.push_back(arg);
    }
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

void writeResult(const fs::path& path, const Extraction& r) {
  enhanced_orb::evaluation::AtomicFile file(path.string());
  cv::FileStorage fs(file.temporary(), cv::FileStorage::WRITE);
  if (!fs.isOpened()) {
    throw std::runtime_error("cannot write " + path.string());
  }
  fs << "keypoints" << keypointMatrix(r.keypoints);
  fs << "descriptors" << r.descriptors;
  fs << "thresholds" << r.cell_thresholds;
  fs << "lambda" << r.lambda;
  fs << "poor_quality" << static_cast<int>(r.poor_quality);
  fs << "inverted" << static_cast<int>(r.inverted);
  fs << "camera_moving" << static_cast<int>(r.camera_moving);
  fs << "judge_ms" << r.timings.judge_ms;
  fs << "enhance_ms" << r.timings.enhance_ms;
  fs << "extract_ms" << r.timings.extractMs();
  fs << "total_ms" << r.timings.totalMs();
  fs.release();
  file.commit();
}

void writeImage(const fs::path& path, const cv::Mat& image) {
  enhanced_orb::evaluation::AtomicFile file(path.string());
  if (!cv::imwrite(file.temporary(), image)) {
    throw std::runtime_error("cannot write " + path.string());
  }
  file.commit();
}

// The deepest folder holding every image.
fs::path commonFolder(const std::vector<std::string>& images) {
  fs::path common;
  for (const std::string& image : images) {
    const fs::path folder = fs::weakly_canonical(fs::absolute(image)).parent_path();
    if (common.empty()) {
      common = folder;
      continue;
    }
    fs::path shared;
    for (auto a = common.begin(), b = folder.begin(); a != common.end() && b != folder.end() && *a == *b; ++a, ++b) {
      shared /= *a;
    }
    common = shared;
  }
  return common;
}

// The files each image writes: DIR/<stem>.*, or, when two images share a name (one per folder, as
// in a data set of scenes), DIR/<folder>/<stem>.* with the image's folder below the images' common
// one. An error when two images would still write the same file or an output would overwrite an
// input. Checked before anything is written.
std::string planOutputs(const Options& opt, std::vector<fs::path>& stems) {
  std::set<std::string> names;
  bool repeated = false;
  for (const std::string& image : opt.images) {
    repeated = !names.insert(fs::path(image).stem().string()).second || repeated;
  }
  const fs::path common = repeated ? commonFolder(opt.images) : fs::path();
  std::map<std::string, std::string> writer;  // output file -> image
  for (const std::string& image : opt.images) {
    fs::path folder;
    if (repeated) {
      folder = fs::weakly_canonical(fs::absolute(image)).parent_path().lexically_relative(common);
      folder = folder == "." ? fs::path() : folder;
    }
    const fs::path stem = fs::path(opt.output) / folder / fs::path(image).stem();
    std::vector<std::string> files{stem.string() + ".yml"};
    if (opt.save_enhanced) {
      files.push_back(stem.string() + "_enhanced.png");
    }
    if (opt.save_annotated) {
      files.push_back(stem.string() + "_annotated.png");
    }
    for (const std::string& file : files) {
      const std::string key = fs::weakly_canonical(file).string();
      if (auto it = writer.find(key); it != writer.end() && it->second != image) {
        return image + " and " + it->second + " would both write " + file +
               ": give the images different names or run once per folder";
      }
      writer[key] = image;
      for (const std::string& input : opt.images) {
        if (enhanced_orb::evaluation::sameFile(input, file)) {
          return "the output " + file + " would overwrite the input " + input;
        }
      }
    }
    stems.push_back(stem);
  }
  return "";
}

// DIR/<stem>.yml, and the enhanced and annotated images when asked for.
void writeOutputs(const Options& opt, const std::string& stem, const Extraction& r) {
  fs::create_directories(fs::path(stem).parent_path());
  writeResult(stem + ".yml", r);
  if (opt.save_enhanced) {
    writeImage(stem + "_enhanced.png", r.image);
  }
  if (opt.save_annotated) {
    std::ostringstream caption;
    caption << r.keypoints.size() << " keypoints, " << cvRound(r.timings.totalMs() * 10) / 10.0 << " ms";
    writeImage(stem + "_annotated.png",
               enhanced_orb::drawAnnotated(r.image, r.keypoints, r.cell_thresholds, caption.str(),
                                           enhanced_orb::DrawOptions{true, false, true, true, 300}));
  }
}

// cv::ORB on `gray` on one thread, whatever --threads says: prints and returns its time in ms.
double timeOpenCv(cv::ORB& opencv, const cv::Mat& gray, const Options& opt) {
  std::vector<cv::KeyPoint> kps;
  cv::Mat descriptors;
  cv::setNumThreads(1);
  const auto start = std::chrono::steady_clock::now();
  opencv.detectAndCompute(gray, cv::noArray(), kps, descriptors);
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  cv::setNumThreads(std::max(opt.params.orb.threads, opt.params.enhance.threads));
  std::cout << ", cv::ORB " << ms << " ms (" << kps.size() << " keypoints)";
  return ms;
}

}  // namespace

int main(int argc, char** argv) {
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "-h" || std::string(argv[i]) == "--help") {
      std::cout << usage();
      return 0;
    }
  }
  Options opt;
  const std::string error = parseArguments(argc, argv, opt);
  if (!error.empty()) {
    std::cerr << "enhanced_orb_extract: " << error << "\n\n" << usage();
    return 2;
  }
  std::vector<fs::path> stems;
  const std::string clash = planOutputs(opt, stems);
  if (!clash.empty()) {
    std::cerr << "enhanced_orb_extract: " << clash << "; nothing written\n";
    return 2;
  }
  try {
    fs::create_directories(opt.output);
    // OpenCV's pool as large as the extraction asks, so that one thread is one thread throughout.
    cv::setNumThreads(std::max(opt.params.orb.threads, opt.params.enhance.threads));
    const enhanced_orb::OrbExtractor extractor(opt.params);
    enhanced_orb::CameraMotion motion;  // the images as one camera's frames, in order
    enhanced_orb::ExtractOptions options;
    Extraction r;  // buffers reused from image to image
    const cv::Ptr<cv::ORB> opencv =
        cv::ORB::create(opt.params.orb.max_features > 0 ? opt.params.orb.max_features : 1000000, 1.2f, 8);
    double sum_judge = 0.0, sum_enhance = 0.0, sum_extract = 0.0, sum_opencv = 0.0;
    int timed = 0;
    int failures = 0;
    for (size_t i = 0; i < opt.images.size(); ++i) {
      const std::string& path = opt.images[i];
      std::string error;
      const cv::Mat gray = enhanced_orb::evaluation::readGrayChecked(path, opt.max_pixels, error);
      if (gray.empty()) {
        std::cerr << "enhanced_orb_extract: skipped " << error << "\n";
        ++failures;
        continue;
      }
      extractor.extract(gray, motion, options, r);
      writeOutputs(opt, stems[i].string(), r);
      std::cout << path << ": " << r.keypoints.size() << " keypoints, judge " << r.timings.judge_ms << " ms, enhance "
                << r.timings.enhance_ms << " ms, extract " << r.timings.extractMs() << " ms, total "
                << r.timings.totalMs() << " ms";
      if (extractor.judgesMotion()) {
        std::cout << ", camera " << (r.camera_moving ? "moving" : "still") << (motion.newScene() ? " (new scene)" : "");
      }
      sum_judge += r.timings.judge_ms;
      sum_enhance += r.timings.enhance_ms;
      sum_extract += r.timings.extractMs();
      ++timed;
      if (opt.time_opencv) {
        sum_opencv += timeOpenCv(*opencv, gray, opt);
      }
      std::cout << "\n";
    }
    if (opt.time_opencv && timed > 0) {
      const double ours = (sum_judge + sum_enhance + sum_extract) / timed;
      std::cout << "mean of " << timed << " images, " << opt.params.orb.threads << " thread(s): judge "
                << sum_judge / timed << " ms + enhance " << sum_enhance / timed << " ms + extract "
                << sum_extract / timed << " ms = " << ours << " ms; cv::ORB (1 thread) " << sum_opencv / timed
                << " ms; ratio " << ours / (sum_opencv / timed) << "\n";
    }
    return failures == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::cerr << "enhanced_orb_extract: " << e.what() << "\n";
    return 1;
  }
}
