// enhanced_orb_compare --paper: the paper's original ORB, its improved ORB (the paper preset) and
// cv::ORB on the same frames, measured as ALGORITHM.md section 4 defines.
#include <algorithm>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/Image.h>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>

#include "enhanced_orb/evaluation/dataset.h"
#include "enhanced_orb/evaluation/degrade.h"
#include "enhanced_orb/evaluation/files.h"
#include "enhanced_orb/evaluation/methods.h"
#include "enhanced_orb/evaluation/metrics.h"
#include "enhanced_orb/orb_extractor.h"
#include "enhanced_orb/ros/conversions.h"
#include "paper_experiments.h"
#include "progress.h"

namespace fs = std::filesystem;
namespace ev = enhanced_orb::evaluation;

namespace enhanced_orb::tools {
namespace {

constexpr const char* kName = "enhanced_orb_compare --paper: ";

struct Frame {
  cv::Mat gray;
  std::int64_t stamp = 0;  // ns; 0 when unknown
  std::string source;      // file, or bag message
};

std::string budgetName(int budget) {
  return budget ? std::to_string(budget) : "unlimited";
}

// The paper's three methods (ALGORITHM.md section 4) at each budget: its original ORB, its improved
// ORB (the paper preset, named "improved" in the output as in the paper) and cv::ORB.
std::vector<ev::Method> methods(const std::vector<int>& budgets) {
  std::vector<ev::Method> out;
  for (int budget : budgets) {
    for (const char* name : {"baseline", "paper", "cv::ORB"}) {
      out.push_back(ev::makeMethod(name, budget));
    }
    out[out.size() - 2].name = "improved";
  }
  return out;
}

// Extraction is timed single-threaded, every method alike; matching may use every core.
ev::Features extractTimed(const ev::Method& m, const cv::Mat& gray) {
  cv::setNumThreads(1);
  ev::Features f = m.run(gray);
  cv::setNumThreads(-1);
  return f;
}

// Figure 6's photometric changes, through the evaluation library's.
struct PhotometricChange {
  std::string kind;  // brightness, gamma, noise
  double value;
  cv::Mat apply(const cv::Mat& gray, std::uint64_t seed) const {
    return kind == "brightness" ? ev::changeBrightness(gray, value)
           : kind == "gamma"    ? ev::applyGamma(gray, value)
                                : ev::addGaussianNoise(gray, value, seed);
  }
};

std::vector<PhotometricChange> changes() {
  std::vector<PhotometricChange> out;
  for (double s : {-0.6, -0.4, -0.2, 0.0, 0.2, 0.4, 0.6}) {
    out.push_back({"brightness", s});
  }
  for (double g : {0.4, 0.67, 1.5, 2.5}) {
    out.push_back({"gamma", g});
  }
  for (double sigma : {5.0, 10.0}) {
    out.push_back({"noise", sigma});
  }
  return out;
}

// Frames from files, each read with the pixel limit; a file that cannot be read is reported and skipped.
std::vector<Frame> readFrames(const std::vector<ev::FrameRef>& refs) {
  std::vector<Frame> frames;
  for (const ev::FrameRef& ref : refs) {
    std::string error;
    cv::Mat gray = ev::readGrayChecked(ref.path, enhanced_orb::kMaxImagePixels, error);
    if (gray.empty()) {
      std::cerr << kName << "skipped " << error << "\n";
      continue;
    }
    frames.push_back({gray, ref.stamp, ref.path});
  }
  return frames;
}

std::vector<Frame> readBag(const std::string& file, const std::string& topic) {
  std::vector<Frame> frames;
  rosbag::Bag bag(file, rosbag::bagmode::Read);
  rosbag::View view(bag, rosbag::TopicQuery(topic));
  for (const rosbag::MessageInstance& m : view) {
    const sensor_msgs::ImageConstPtr msg = m.instantiate<sensor_msgs::Image>();
    if (!msg) {
      continue;
    }
    const enhanced_orb::GrayImage g = enhanced_orb::toGrayImage(msg);
    if (!g.error.empty()) {
      std::cerr << kName << "skipped a message: " << g.error << "\n";
      continue;
    }
    frames.push_back({g.gray.clone(), static_cast<std::int64_t>(msg->header.stamp.toNSec()),
                      file + " message " + std::to_string(frames.size())});
  }
  return frames;
}

std::string cpuModel() {
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0) {
      return line.substr(line.find(':') + 2);
    }
  }
  return "unknown";
}

// The frames of the one input the options name, with the poses and calibration a EuRoC sequence has.
struct Input {
  std::vector<Frame> frames;
  std::optional<ev::Camera> camera;
  std::optional<ev::Trajectory> trajectory;
  std::string description;
};

Input readInput(const PaperOptions& o) {
  Input in;
  if (!o.euroc.empty()) {
    const ev::EurocSequence seq = ev::readEuroc(o.euroc);
    in.frames = readFrames(seq.frames);
    in.camera = seq.camera;
    in.trajectory = seq.trajectory;
    in.description = "EuRoC " + fs::absolute(seq.mav0).lexically_normal().string() + " cam0";
  } else if (!o.images.empty()) {
    in.frames = readFrames(ev::readImageFolder(o.images));
    in.description = "images " + o.images;
  } else {
    in.frames = readBag(o.bag, o.topic);
    in.description = "bag " + o.bag + " " + o.topic;
  }
  std::vector<Frame>& frames = in.frames;
  frames.erase(std::remove_if(frames.begin(), frames.end(), [](const Frame& f) { return f.gray.empty(); }),
               frames.end());
  if (o.max_frames > 0 && static_cast<int>(frames.size()) > o.max_frames) {
    frames.resize(o.max_frames);
  }
  return in;
}

// Every method on every frame: frames.csv (Figure 7 / Table 4) and the means, table2.csv (Table 2).
// A frame on which a method fails (one pixel wide, say) is reported and left out for every method,
// so that all compare the same frames; `frames` keeps those that are left. Returns the number left out.
int extractAll(const std::vector<ev::Method>& all, std::vector<Frame>& frames,
               std::vector<std::vector<ev::Features>>& features, ev::AtomicTextFile& per_frame_file,
               ev::AtomicTextFile& table2_file) {
  features.assign(all.size(), {});
  std::ostream& per_frame = per_frame_file.out();
  per_frame << "frame,stamp,method,budget,keypoints,ms\n";
  std::vector<Frame> kept;
  int skipped = 0;
  for (size_t i = 0; i < frames.size(); ++i) {
    progress("extracting", i, frames.size());
    std::vector<ev::Features> f(all.size());
    try {
      for (size_t m = 0; m < all.size(); ++m) {
        f[m] = extractTimed(all[m], frames[i].gray);
      }
    } catch (const std::exception& e) {
      std::cerr << "\n"
                << kName << "skipped " << frames[i].source << " (" << frames[i].gray.cols << " x "
                << frames[i].gray.rows << "): " << e.what() << "\n";
      ++skipped;
      continue;
    }
    kept.push_back(frames[i]);
    for (size_t m = 0; m < all.size(); ++m) {
      per_frame << kept.size() - 1 << "," << frames[i].stamp << "," << all[m].name << "," << budgetName(all[m].budget)
                << "," << f[m].keypoints.size() << "," << f[m].ms << "\n";
      features[m].push_back(std::move(f[m]));
    }
  }
  progress("extracting", frames.size(), frames.size());
  frames = std::move(kept);
  std::ostream& table2 = table2_file.out();
  table2 << "method,budget,frames,keypoints,ms\n";
  for (size_t m = 0; m < all.size() && !frames.empty(); ++m) {
    double kp = 0.0, ms = 0.0;
    for (const ev::Features& f : features[m]) {
      kp += f.keypoints.size();
      ms += f.ms;
    }
    table2 << all[m].name << "," << budgetName(all[m].budget) << "," << frames.size() << "," << kp / frames.size()
           << "," << ms / frames.size() << "\n";
  }
  return skipped;
}

// Photometric changes of every `every`-th frame against the frame itself (Figure 6, Table 3:
// identity ground truth), into figure6.csv. Returns the number of frames changed.
size_t photometricChanges(const std::vector<ev::Method>& all, const std::vector<Frame>& frames,
                          const std::vector<std::vector<ev::Features>>& features, int every, ev::AtomicTextFile& file) {
  struct Sum {
    double keypoints = 0, ms = 0, repeatability = 0;
    long matches = 0, correct = 0;
    int n = 0;
  };
  const std::vector<PhotometricChange> photometric = changes();
  std::map<std::tuple<size_t, size_t>, Sum> sums;  // (method, change)
  std::vector<size_t> sampled;
  for (size_t i = 0; i < frames.size(); i += every) {
    sampled.push_back(i);
  }
  for (size_t k = 0; k < sampled.size(); ++k) {
    progress("photometric changes", k, sampled.size());
    const size_t i = sampled[k];
    for (size_t c = 0; c < photometric.size(); ++c) {
      const cv::Mat changed = photometric[c].apply(frames[i].gray, 1000 + i);
      for (size_t m = 0; m < all.size(); ++m) {
        const ev::Features& ref = features[m][i];
        const ev::Features f = extractTimed(all[m], changed);
        const ev::MatchCounts counts =
            ev::matchAndCount(ref.keypoints, ref.descriptors, f.keypoints, f.descriptors, ev::identity());
        Sum& s = sums[{m, c}];
        s.keypoints += f.keypoints.size();
        s.ms += f.ms;
        s.matches += counts.matches;
        s.correct += counts.correct;
        s.repeatability += ev::repeatability(ref.keypoints, f.keypoints);
        ++s.n;
      }
    }
  }
  progress("photometric changes", sampled.size(), sampled.size());
  std::ostream& figure6 = file.out();
  figure6 << "method,budget,change,value,frames,keypoints,ms,matches,correct,accuracy,repeatability\n";
  for (const auto& [key, s] : sums) {
    const auto [m, c] = key;
    figure6 << all[m].name << "," << budgetName(all[m].budget) << "," << photometric[c].kind << ","
            << photometric[c].value << "," << s.n << "," << s.keypoints / s.n << "," << s.ms / s.n << ","
            << static_cast<double>(s.matches) / s.n << "," << static_cast<double>(s.correct) / s.n << ","
            << (s.matches ? static_cast<double>(s.correct) / s.matches : 0.0) << "," << s.repeatability / s.n << "\n";
  }
  return sampled.size();
}

// The pairs `step` frames apart, one every `pair_every`, that the epipolar test can judge; pairs
// whose camera did not move are counted in `static_pairs` instead.
std::vector<std::pair<size_t, ev::GroundTruth>> judgedPairs(const Input& in, int step, int pair_every,
                                                            int& static_pairs) {
  std::vector<std::pair<size_t, ev::GroundTruth>> judged;
  static_pairs = 0;
  for (size_t i = 0; i + step < in.frames.size(); i += pair_every) {
    const auto p1 = in.trajectory->at(in.frames[i].stamp);
    const auto p2 = in.trajectory->at(in.frames[i + step].stamp);
    if (p1 && p2 && ev::isStatic(ev::groundTruthPose(*in.camera, *p1, *in.camera, *p2))) {
      ++static_pairs;
    } else if (p1 && p2) {
      judged.emplace_back(i, ev::epipolar(*in.camera, *p1, *p2));
    }
  }
  return judged;
}

// Frame pairs some steps apart (Table 3), judged by the sequence's poses, into pairs.csv.
void framePairs(const std::vector<ev::Method>& all, const Input& in,
                const std::vector<std::vector<ev::Features>>& features, const PaperOptions& o,
                ev::AtomicTextFile& file) {
  std::ostream& pairs = file.out();
  pairs << "method,budget,steps,pairs,static_excluded,matches,correct,accuracy\n";
  if (!in.camera || !in.trajectory) {
    std::cerr << kName << "no ground-truth poses and calibration: frame pairs skipped\n";
    return;
  }
  for (int step : o.steps) {
    int static_pairs = 0;  // no motion: the epipolar test says nothing, so they are not scored
    const auto judged = judgedPairs(in, step, o.pair_every, static_pairs);
    if (static_pairs > 0) {
      std::cerr << kName << static_pairs << " frame pairs +" << step << " without motion (under 2 cm) are not scored\n";
    }
    for (size_t m = 0; m < all.size(); ++m) {
      progress("pairs +" + std::to_string(step) + " " + all[m].name, m, all.size());
      long matches = 0, correct = 0;
      for (const auto& [i, truth] : judged) {
        const ev::Features& a = features[m][i];
        const ev::Features& b = features[m][i + step];
        const ev::MatchCounts counts = ev::matchAndCount(a.keypoints, a.descriptors, b.keypoints, b.descriptors, truth);
        matches += counts.matches;
        correct += counts.correct;
      }
      const double n = std::max<size_t>(1, judged.size());
      pairs << all[m].name << "," << budgetName(all[m].budget) << "," << step << "," << judged.size() << ","
            << static_pairs << "," << matches / n << "," << correct / n << ","
            << (matches ? static_cast<double>(correct) / matches : 0.0) << "\n";
    }
    progress("pairs +" + std::to_string(step), 1, 1);
  }
}

}  // namespace

int runPaperExperiments(const PaperOptions& o) {
  Input in = readInput(o);
  if (in.frames.empty()) {
    std::cerr << kName << "no readable frame in the input\n";
    return 1;
  }
  fs::create_directories(o.output);
  const fs::path out = o.output;
  const std::vector<ev::Method> all = methods(o.budgets);
  ev::AtomicTextFile per_frame((out / "frames.csv").string()), table2((out / "table2.csv").string()),
      figure6((out / "figure6.csv").string()), pairs((out / "pairs.csv").string()),
      meta_file((out / "meta.csv").string());
  std::vector<std::vector<ev::Features>> features;
  const int skipped = extractAll(all, in.frames, features, per_frame, table2);
  if (in.frames.empty()) {
    std::cerr << kName << "no frame could be processed\n";
    return 1;
  }
  const size_t changed = photometricChanges(all, in.frames, features, o.every, figure6);
  framePairs(all, in, features, o, pairs);
  std::ostream& meta = meta_file.out();
  meta << "key,value\n"
       << "input," << in.description << "\n"
       << "frames," << in.frames.size() << "\n"
       << "frames skipped," << skipped << "\n"
       << "size," << in.frames[0].gray.cols << "x" << in.frames[0].gray.rows << "\n"
       << "photometric frames," << changed << " (every " << o.every << ")\n"
       << "cpu," << cpuModel() << "\n"
       << "cores," << cv::getNumberOfCPUs() << "\n"
       << "opencv," << CV_VERSION << "\n";
  for (ev::AtomicTextFile* f : {&per_frame, &table2, &figure6, &pairs, &meta_file}) {
    f->commit();  // only now do the results replace any earlier ones
  }
  std::cout << kName << in.frames.size() << " frames (" << skipped << " skipped); wrote " << out.string()
            << "/{frames,table2,figure6,pairs,meta}.csv\n";
  return 0;
}

}  // namespace enhanced_orb::tools
