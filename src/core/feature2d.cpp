#include "enhanced_orb/feature2d.h"

#include <fstream>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "stopwatch.h"

namespace enhanced_orb {
namespace {

// The 8-bit gray image a Feature2D call reads: gray as it is, BGR and BGRA by luma, as cv::ORB.
cv::Mat grayOf(const cv::Mat& image) {
  if (image.empty() || image.type() == CV_8UC1) {
    return image;
  }
  cv::Mat gray;
  if (image.type() == CV_8UC3) {
    cv::cvtColor(image, gray, cv::COLOR_BGR2GRAY);
  } else if (image.type() == CV_8UC4) {
    cv::cvtColor(image, gray, cv::COLOR_BGRA2GRAY);
  } else {
    CV_Error(cv::Error::StsUnsupportedFormat,
             "enhanced_orb::ORB: expected an 8-bit gray, BGR or BGRA image, got " + cv::typeToString(image.type()));
  }
  return gray;
}

// A FileStorage value as the text setParam() reads.
std::string textOf(const cv::FileNode& value) {
  if (value.isString()) {
    return static_cast<std::string>(value);
  }
  if (value.isInt()) {
    return std::to_string(static_cast<int>(value));
  }
  if (value.isReal()) {
    return cv::format("%.17g", static_cast<double>(value));
  }
  return std::string();
}

}  // namespace

Params presetParams(const std::string& name) {
  if (name == "baseline") {
    return Params::baseline();
  }
  Preset preset;
  if (!parsePreset(name, preset)) {
    throw std::invalid_argument("unknown preset '" + name + "' (" + presetNames() + " or baseline)");
  }
  return Params::preset(preset);
}

Params readParams(const cv::FileNode& node, const Params& base, std::vector<std::string>* given) {
  const cv::FileNode preset = node["preset"];
  Params params = preset.isString() ? presetParams(static_cast<std::string>(preset)) : base;
  std::vector<std::string> problems;
  if (given) {
    given->clear();
  }
  for (const std::string& name : paramNames()) {
    const cv::FileNode value = node[name];
    if (!value.empty()) {
      if (given) {
        given->push_back(name);
      }
      const std::string problem = setParam(params, name, textOf(value));
      if (!problem.empty()) {
        problems.push_back(problem);
      }
    }
  }
  const std::vector<std::string> invalid = validate(params);
  problems.insert(problems.end(), invalid.begin(), invalid.end());
  if (!problems.empty()) {
    throw std::invalid_argument(joinMessages(problems));
  }
  return params;
}

Params readParamsFile(const std::string& path, const Params& base, std::vector<std::string>* given) {
  std::ifstream file(path);
  if (!file) {
    throw std::invalid_argument("cannot read parameters from '" + path + "'");
  }
  // OpenCV's YAML reader takes neither a missing directive nor comments after a value (which ROS
  // files have): the text it reads has the directive and no comments.
  std::string yaml = "%YAML:1.0\n";
  std::string line;
  while (std::getline(file, line)) {
    if (line.rfind("%YAML", 0) == 0) {
      continue;
    }
    const size_t comment = line.find('#');
    yaml += line.substr(0, comment) + "\n";
  }
  try {
    cv::FileStorage fs(yaml, cv::FileStorage::READ | cv::FileStorage::MEMORY | cv::FileStorage::FORMAT_YAML);
    return readParams(fs.root(), base, given);
  } catch (const cv::Exception& e) {
    throw std::invalid_argument("'" + path + "' is not YAML OpenCV reads: " + e.err);
  }
}

cv::Ptr<ORB> ORB::create(const Params& params) {
  return cv::Ptr<ORB>(new ORB(params));
}

cv::Ptr<ORB> ORB::create(const std::string& preset) {
  return create(presetParams(preset));
}

void ORB::setParams(const Params& params) {
  extractor_ = OrbExtractor(params);
}

void ORB::detectAndCompute(cv::InputArray image, cv::InputArray mask, std::vector<cv::KeyPoint>& keypoints,
                           cv::OutputArray descriptors, bool useProvidedKeypoints) {
  Stopwatch clock;
  const cv::Mat gray = grayOf(image.getMat());
  const double convert_ms = clock.lap();
  const cv::Mat mask_mat = mask.getMat();
  if (!mask_mat.empty() && (mask_mat.type() != CV_8UC1 || mask_mat.size() != gray.size())) {
    CV_Error(cv::Error::StsBadArg, "enhanced_orb::ORB: the mask must be 8-bit, one channel, of the image's size");
  }
  if (useProvidedKeypoints) {
    cv::Mat described;
    extractor_.describe(gray, keypoints, described);
    if (descriptors.needed()) {
      described.copyTo(descriptors);
    }
    return;
  }
  ExtractOptions options;
  options.mask = mask_mat;
  extractor_.extract(gray, motion_, options, result_);
  result_.timings.convert_ms = convert_ms;
  keypoints = result_.keypoints;
  if (descriptors.needed()) {
    result_.descriptors.copyTo(descriptors);
  }
}

void ORB::clear() {
  motion_.reset();
}

void ORB::write(cv::FileStorage& fs) const {
  writeFormat(fs);
  fs << "name" << getDefaultName();
  for (const std::string& name : paramNames()) {
    fs << name << paramText(params(), name).value_or("");
  }
}

void ORB::read(const cv::FileNode& node) {
  setParams(readParams(node, params()));
}

}  // namespace enhanced_orb
