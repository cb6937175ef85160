// enhanced_orb_evaluate: baseline ORB, enhanced ORB and cv::ORB on the same frames, measured as
// ALGORITHM.md section 4 defines, at two budgets (every corner; 1000 features, 8 levels, 1.2).
// Writes CSV files that scripts/results.py turns into plots and docs/RESULTS.md.
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

namespace fs = std::filesystem;
namespace ev = enhanced_orb::evaluation;
using enhanced_orb::OrbExtractor;
using enhanced_orb::Params;

namespace {

const char* const kUsage = R"(usage: enhanced_orb_evaluate INPUT [options]

INPUT (one of):
  --euroc DIR            a EuRoC sequence in ASL layout (DIR or DIR/mav0): cam0 frames; frame pairs
                         are judged by the ground-truth poses where the sequence has them
  --images DIR           every .png/.jpg/.pgm image of DIR, in name order
  --bag FILE --topic T   the sensor_msgs/Image messages of topic T
options:
  --output DIR           where to write the CSV files (default: results)
  --every N              photometric changes on every N-th frame (default 10)
  --pair-every N         frame pairs start every N-th frame (default 5)
  --steps K[,K...]       frame pairs K frames apart (default 1,5,10)
  --max-frames N         use at most N frames
  --budgets K[,K...]     feature budgets, 0 = every corner (default 0,1000)
  -h, --help             this text

Writes frames.csv (per frame and method: keypoints, ms), table2.csv (means), figure6.csv
(photometric changes: keypoints, ms, matches, correct, accuracy, repeatability), pairs.csv
(frame pairs: matches, correct, accuracy; pairs without motion are counted in static_excluded and
not scored) and meta.csv (input, machine, versions, frames skipped). The files are written under
temporary names and renamed together at the end. An image that cannot be read, is over 32 Mpixel
or that a method cannot process (one pixel wide, say) is reported and left out for every method.
exit codes: 0 done, 1 no usable frame or an output could not be written, 2 bad arguments.
)";

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

void progress(const std::string& what, size_t done, size_t total) {
  const int width = 30;
  const int filled = total ? static_cast<int>(width * done / total) : width;
  std::cerr << "\r" << std::left << std::setw(22) << what << " [" << std::string(filled, '#')
            << std::string(width - filled, '.') << "] " << done << "/" << total << std::flush;
  if (done == total) {
    std::cerr << "\n";
  }
}

// A CSV file written under a temporary name, renamed by commit(): nothing half-written is left.
class CsvFile {
public:
  explicit CsvFile(const fs::path& path) : file_(path.string()), out_(file_.temporary()) {
    if (!out_) {
      throw std::runtime_error("cannot write " + path.string());
    }
  }
  std::ofstream& out() { return out_; }
  void commit() {
    out_.close();
    if (!out_) {
      throw std::runtime_error("cannot write " + file_.path());
    }
    file_.commit();
  }

private:
  ev::AtomicFile file_;
  std::ofstream out_;
};

// Frames from files, each read with the pixel limit; a file that cannot be read is reported and skipped.
std::vector<Frame> readFrames(const std::vector<ev::FrameRef>& refs) {
  std::vector<Frame> frames;
  for (const ev::FrameRef& ref : refs) {
    std::string error;
    cv::Mat gray = ev::readGrayChecked(ref.path, enhanced_orb::kMaxImagePixels, error);
    if (gray.empty()) {
      std::cerr << "enhanced_orb_evaluate: skipped " << error << "\n";
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
      std::cerr << "enhanced_orb_evaluate: skipped a message: " << g.error << "\n";
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

struct Options {
  std::string euroc, images, bag, topic, output = "results";
  int every = 10, pair_every = 5, max_frames = 0;
  std::vector<int> steps{1, 5, 10};
  std::vector<int> budgets{0, 1000};
};

bool parse(int argc, char** argv, Options& o, std::string& error) {
  auto number = [&](const std::string& v, int& out) {
    try {
      size_t used = 0;
      out = std::stoi(v, &used);
      return used == v.size() && out > 0;
    } catch (const std::exception&) {
      return false;
    }
  };
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      error.clear();
      return false;
    }
    if (i + 1 >= argc) {
      error = "missing value after " + arg;
      return false;
    }
    const std::string v = argv[++i];
    if (arg == "--euroc") {
      o.euroc = v;
    } else if (arg == "--images") {
      o.images = v;
    } else if (arg == "--bag") {
      o.bag = v;
    } else if (arg == "--topic") {
      o.topic = v;
    } else if (arg == "--output") {
      o.output = v;
    } else if (arg == "--every" || arg == "--pair-every" || arg == "--max-frames") {
      int& target = arg == "--every" ? o.every : arg == "--pair-every" ? o.pair_every : o.max_frames;
      if (!number(v, target)) {
        error = "invalid value for " + arg + ": '" + v + "'";
        return false;
      }
    } else if (arg == "--budgets") {
      o.budgets.clear();
      std::istringstream in(v);
      std::string k;
      while (std::getline(in, k, ',')) {
        int budget = 0;
        if (k != "0" && !number(k, budget)) {
          error = "invalid --budgets '" + v + "'";
          return false;
        }
        o.budgets.push_back(budget);
      }
    } else if (arg == "--steps") {
      o.steps.clear();
      std::istringstream in(v);
      std::string k;
      while (std::getline(in, k, ',')) {
        int step = 0;
        if (!number(k, step)) {
          error = "invalid --steps '" + v + "'";
          return false;
        }
        o.steps.push_back(step);
      }
    } else {
      error = "unknown option " + arg;
      return false;
    }
  }
  const int inputs = !o.euroc.empty() + !o.images.empty() + !o.bag.empty();
  if (inputs != 1 || (!o.bag.empty() && o.topic.empty())) {
    error = "give exactly one of --euroc DIR, --images DIR, --bag FILE --topic T";
    return false;
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  std::string error;
  if (argc < 2 || !parse(argc, argv, opt, error)) {
    std::cerr << (error.empty() ? "" : "enhanced_orb_evaluate: " + error + "\n\n") << kUsage;
    return error.empty() ? 0 : 2;
  }
  try {
    std::vector<Frame> frames;
    std::optional<ev::Camera> camera;
    std::optional<ev::Trajectory> trajectory;
    std::string input;
    if (!opt.euroc.empty()) {
      const ev::EurocSequence seq = ev::readEuroc(opt.euroc);
      frames = readFrames(seq.frames);
      camera = seq.camera;
      trajectory = seq.trajectory;
      input = "EuRoC " + fs::absolute(seq.mav0).lexically_normal().string() + " cam0";
    } else if (!opt.images.empty()) {
      frames = readFrames(ev::readImageFolder(opt.images));
      input = "images " + opt.images;
    } else {
      frames = readBag(opt.bag, opt.topic);
      input = "bag " + opt.bag + " " + opt.topic;
    }
    frames.erase(std::remove_if(frames.begin(), frames.end(), [](const Frame& f) { return f.gray.empty(); }),
                 frames.end());
    if (opt.max_frames > 0 && static_cast<int>(frames.size()) > opt.max_frames) {
      frames.resize(opt.max_frames);
    }
    if (frames.empty()) {
      std::cerr << "enhanced_orb_evaluate: no readable frame in the input\n";
      return 1;
    }
    fs::create_directories(opt.output);
    const fs::path out = opt.output;
    const std::vector<ev::Method> all = methods(opt.budgets);

    // Per frame (Figure 7 / Table 4) and the means (Table 2). A frame on which a method fails (one
    // pixel wide, say) is reported and left out for every method, so that all compare the same frames.
    std::vector<std::vector<ev::Features>> features(all.size());
    CsvFile per_frame_file(out / "frames.csv");
    std::ofstream& per_frame = per_frame_file.out();
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
        std::cerr << "\nenhanced_orb_evaluate: skipped " << frames[i].source << " (" << frames[i].gray.cols << " x "
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
    if (frames.empty()) {
      std::cerr << "enhanced_orb_evaluate: no frame could be processed\n";
      return 1;
    }
    CsvFile table2_file(out / "table2.csv");
    std::ofstream& table2 = table2_file.out();
    table2 << "method,budget,frames,keypoints,ms\n";
    for (size_t m = 0; m < all.size(); ++m) {
      double kp = 0.0, ms = 0.0;
      for (const ev::Features& f : features[m]) {
        kp += f.keypoints.size();
        ms += f.ms;
      }
      table2 << all[m].name << "," << budgetName(all[m].budget) << "," << frames.size() << "," << kp / frames.size()
             << "," << ms / frames.size() << "\n";
    }

    // Photometric changes of one frame (Figure 6, Table 3): identity ground truth.
    struct Sum {
      double keypoints = 0, ms = 0, repeatability = 0;
      long matches = 0, correct = 0;
      int n = 0;
    };
    const std::vector<PhotometricChange> photometric = changes();
    std::map<std::tuple<size_t, size_t>, Sum> sums;  // (method, change)
    std::vector<size_t> sampled;
    for (size_t i = 0; i < frames.size(); i += opt.every) {
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
    CsvFile figure6_file(out / "figure6.csv");
    std::ofstream& figure6 = figure6_file.out();
    figure6 << "method,budget,change,value,frames,keypoints,ms,matches,correct,accuracy,repeatability\n";
    for (const auto& [key, s] : sums) {
      const auto [m, c] = key;
      figure6 << all[m].name << "," << budgetName(all[m].budget) << "," << photometric[c].kind << ","
              << photometric[c].value << "," << s.n << "," << s.keypoints / s.n << "," << s.ms / s.n << ","
              << static_cast<double>(s.matches) / s.n << "," << static_cast<double>(s.correct) / s.n << ","
              << (s.matches ? static_cast<double>(s.correct) / s.matches : 0.0) << "," << s.repeatability / s.n << "\n";
    }

    // Frame pairs some steps apart (Table 3): epipolar ground truth from the dataset's poses.
    CsvFile pairs_file(out / "pairs.csv");
    std::ofstream& pairs = pairs_file.out();
    pairs << "method,budget,steps,pairs,static_excluded,matches,correct,accuracy\n";
    if (camera && trajectory) {
      for (int step : opt.steps) {
        std::vector<std::pair<size_t, ev::GroundTruth>> judged;
        int static_pairs = 0;  // no motion: the epipolar test says nothing, so they are not scored
        for (size_t i = 0; i + step < frames.size(); i += opt.pair_every) {
          const auto p1 = trajectory->at(frames[i].stamp);
          const auto p2 = trajectory->at(frames[i + step].stamp);
          if (p1 && p2 && ev::isStatic(ev::groundTruthPose(*camera, *p1, *camera, *p2))) {
            ++static_pairs;
          } else if (p1 && p2) {
            judged.emplace_back(i, ev::epipolar(*camera, *p1, *p2));
          }
        }
        if (static_pairs > 0) {
          std::cerr << "enhanced_orb_evaluate: " << static_pairs << " frame pairs +" << step
                    << " without motion (under 2 cm) are not scored\n";
        }
        for (size_t m = 0; m < all.size(); ++m) {
          progress("pairs +" + std::to_string(step) + " " + all[m].name, m, all.size());
          long matches = 0, correct = 0;
          for (const auto& [i, truth] : judged) {
            const ev::Features& a = features[m][i];
            const ev::Features& b = features[m][i + step];
            const ev::MatchCounts counts =
                ev::matchAndCount(a.keypoints, a.descriptors, b.keypoints, b.descriptors, truth);
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
    } else {
      std::cerr << "enhanced_orb_evaluate: no ground-truth poses and calibration: frame pairs skipped\n";
    }

    CsvFile meta_file(out / "meta.csv");
    std::ofstream& meta = meta_file.out();
    meta << "key,value\n"
         << "input," << input << "\n"
         << "frames," << frames.size() << "\n"
         << "frames skipped," << skipped << "\n"
         << "size," << frames[0].gray.cols << "x" << frames[0].gray.rows << "\n"
         << "photometric frames," << sampled.size() << " (every " << opt.every << ")\n"
         << "cpu," << cpuModel() << "\n"
         << "cores," << cv::getNumberOfCPUs() << "\n"
         << "opencv," << CV_VERSION << "\n";
    for (CsvFile* f : {&per_frame_file, &table2_file, &figure6_file, &pairs_file, &meta_file}) {
      f->commit();  // only now do the results replace any earlier ones
    }
    std::cout << "enhanced_orb_evaluate: " << frames.size() << " frames (" << skipped << " skipped); wrote "
              << out.string() << "/{frames,table2,"
              << "figure6,pairs,meta}.csv\n";
  } catch (const std::exception& e) {
    std::cerr << "\nenhanced_orb_evaluate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
