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
  -h, --help             this text

Writes frames.csv (per frame and method: keypoints, ms), table2.csv (means), figure6.csv
(photometric changes: keypoints, ms, matches, correct, accuracy, repeatability), pairs.csv
(frame pairs: matches, correct, accuracy) and meta.csv (input, machine, versions).
)";

struct Frame {
  cv::Mat gray;
  std::int64_t stamp = 0;  // ns; 0 when unknown
};

struct Features {
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  double ms = 0.0;
};

struct Method {
  std::string name;
  int budget;  // 0 = every corner
  std::function<Features(const cv::Mat&)> run;
};

std::string budgetName(int budget) {
  return budget ? std::to_string(budget) : "unlimited";
}

double msSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

std::vector<Method> methods() {
  std::vector<Method> out;
  for (int budget : {0, 1000}) {
    for (const std::string name : {"baseline", "improved"}) {
      Params p = name == "baseline" ? Params::baseline() : Params::paper();
      p.orb.max_features = budget;
      auto extractor = std::make_shared<OrbExtractor>(p);
      out.push_back({name, budget, [extractor](const cv::Mat& gray) {
                       const auto start = std::chrono::steady_clock::now();
                       enhanced_orb::Extraction r = extractor->extract(gray);
                       return Features{std::move(r.keypoints), r.descriptors, msSince(start)};
                     }});
    }
    // cv::ORB keeps at most nfeatures: "every corner" asks for more than any frame has.
    cv::Ptr<cv::ORB> orb = cv::ORB::create(budget ? budget : 1000000, 1.2f, 8);
    out.push_back({"cv::ORB", budget, [orb](const cv::Mat& gray) {
                     Features f;
                     const auto start = std::chrono::steady_clock::now();
                     orb->detectAndCompute(gray, cv::noArray(), f.keypoints, f.descriptors);
                     f.ms = msSince(start);
                     return f;
                   }});
  }
  return out;
}

// Extraction is timed single-threaded, every method alike; matching may use every core.
Features extractTimed(const Method& m, const cv::Mat& gray) {
  cv::setNumThreads(1);
  Features f = m.run(gray);
  cv::setNumThreads(-1);
  return f;
}

struct PhotometricChange {
  std::string kind;  // brightness, gamma, noise
  double value;
  cv::Mat apply(const cv::Mat& gray, std::uint64_t seed) const {
    cv::Mat out;
    if (kind == "brightness") {
      gray.convertTo(out, CV_8U, 1.0 + value);  // I' = saturate(I (1 + s))
    } else if (kind == "gamma") {
      cv::Mat lut(1, 256, CV_8U);
      for (int i = 0; i < 256; ++i) {
        lut.at<uchar>(i) = cv::saturate_cast<uchar>(255.0 * std::pow(i / 255.0, value));
      }
      cv::LUT(gray, lut, out);
    } else {
      cv::Mat noise(gray.size(), CV_32F);
      cv::RNG rng(seed);
      rng.fill(noise, cv::RNG::NORMAL, 0.0, value);
      cv::Mat g;
      gray.convertTo(g, CV_32F);
      cv::Mat(g + noise).convertTo(out, CV_8U);
    }
    return out;
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

std::vector<fs::path> sortedFiles(const fs::path& dir, const std::vector<std::string>& extensions) {
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), ::tolower);
    if (std::find(extensions.begin(), extensions.end(), ext) != extensions.end()) {
      files.push_back(entry.path());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

std::vector<Frame> readEuroc(const fs::path& mav0) {
  std::vector<Frame> frames;
  std::ifstream csv(mav0 / "cam0" / "data.csv");
  std::string line;
  while (std::getline(csv, line)) {
    if (line.empty() || line[0] == '#') {
      continue;
    }
    const size_t comma = line.find(',');
    std::string name = line.substr(comma + 1);
    name.erase(std::remove(name.begin(), name.end(), '\r'), name.end());
    const fs::path file = mav0 / "cam0" / "data" / name;
    if (fs::exists(file)) {
      frames.push_back({cv::imread(file.string(), cv::IMREAD_GRAYSCALE), std::stoll(line.substr(0, comma))});
    }
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
    frames.push_back({g.gray.clone(), static_cast<std::int64_t>(msg->header.stamp.toNSec())});
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
      fs::path mav0 = opt.euroc;
      if (fs::is_directory(mav0 / "mav0")) {
        mav0 /= "mav0";
      }
      frames = readEuroc(mav0);
      camera = ev::readCamera(mav0.string(), "cam0");
      trajectory = ev::Trajectory::read(mav0.string());
      input = "EuRoC " + fs::absolute(mav0).lexically_normal().string() + " cam0";
    } else if (!opt.images.empty()) {
      for (const fs::path& f : sortedFiles(opt.images, {".png", ".jpg", ".jpeg", ".pgm", ".bmp"})) {
        frames.push_back({cv::imread(f.string(), cv::IMREAD_GRAYSCALE), 0});
      }
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
    const std::vector<Method> all = methods();

    // Per frame (Figure 7 / Table 4) and the means (Table 2).
    std::vector<std::vector<Features>> features(all.size());
    std::ofstream per_frame(out / "frames.csv");
    per_frame << "frame,stamp,method,budget,keypoints,ms\n";
    for (size_t i = 0; i < frames.size(); ++i) {
      progress("extracting", i, frames.size());
      for (size_t m = 0; m < all.size(); ++m) {
        features[m].push_back(extractTimed(all[m], frames[i].gray));
        per_frame << i << "," << frames[i].stamp << "," << all[m].name << "," << budgetName(all[m].budget) << ","
                  << features[m].back().keypoints.size() << "," << features[m].back().ms << "\n";
      }
    }
    progress("extracting", frames.size(), frames.size());
    std::ofstream table2(out / "table2.csv");
    table2 << "method,budget,frames,keypoints,ms\n";
    for (size_t m = 0; m < all.size(); ++m) {
      double kp = 0.0, ms = 0.0;
      for (const Features& f : features[m]) {
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
          const Features& ref = features[m][i];
          const Features f = extractTimed(all[m], changed);
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
    std::ofstream figure6(out / "figure6.csv");
    figure6 << "method,budget,change,value,frames,keypoints,ms,matches,correct,accuracy,repeatability\n";
    for (const auto& [key, s] : sums) {
      const auto [m, c] = key;
      figure6 << all[m].name << "," << budgetName(all[m].budget) << "," << photometric[c].kind << ","
              << photometric[c].value << "," << s.n << "," << s.keypoints / s.n << "," << s.ms / s.n << ","
              << static_cast<double>(s.matches) / s.n << "," << static_cast<double>(s.correct) / s.n << ","
              << (s.matches ? static_cast<double>(s.correct) / s.matches : 0.0) << "," << s.repeatability / s.n << "\n";
    }

    // Frame pairs some steps apart (Table 3): epipolar ground truth from the dataset's poses.
    std::ofstream pairs(out / "pairs.csv");
    pairs << "method,budget,steps,pairs,matches,correct,accuracy\n";
    if (camera && trajectory) {
      for (int step : opt.steps) {
        std::vector<std::pair<size_t, ev::GroundTruth>> judged;
        for (size_t i = 0; i + step < frames.size(); i += opt.pair_every) {
          const auto p1 = trajectory->at(frames[i].stamp);
          const auto p2 = trajectory->at(frames[i + step].stamp);
          if (p1 && p2) {
            judged.emplace_back(i, ev::epipolar(*camera, *p1, *p2));
          }
        }
        for (size_t m = 0; m < all.size() && !judged.empty(); ++m) {
          progress("pairs +" + std::to_string(step) + " " + all[m].name, m, all.size());
          long matches = 0, correct = 0;
          for (const auto& [i, truth] : judged) {
            const Features& a = features[m][i];
            const Features& b = features[m][i + step];
            const ev::MatchCounts counts =
                ev::matchAndCount(a.keypoints, a.descriptors, b.keypoints, b.descriptors, truth);
            matches += counts.matches;
            correct += counts.correct;
          }
          pairs << all[m].name << "," << budgetName(all[m].budget) << "," << step << "," << judged.size() << ","
                << static_cast<double>(matches) / judged.size() << "," << static_cast<double>(correct) / judged.size()
                << "," << (matches ? static_cast<double>(correct) / matches : 0.0) << "\n";
        }
        progress("pairs +" + std::to_string(step), 1, 1);
      }
    } else {
      std::cerr << "enhanced_orb_evaluate: no ground-truth poses and calibration: frame pairs skipped\n";
    }

    std::ofstream meta(out / "meta.csv");
    meta << "key,value\n"
         << "input," << input << "\n"
         << "frames," << frames.size() << "\n"
         << "size," << frames[0].gray.cols << "x" << frames[0].gray.rows << "\n"
         << "photometric frames," << sampled.size() << " (every " << opt.every << ")\n"
         << "cpu," << cpuModel() << "\n"
         << "cores," << cv::getNumberOfCPUs() << "\n"
         << "opencv," << CV_VERSION << "\n";
    std::cout << "enhanced_orb_evaluate: " << frames.size() << " frames; wrote " << out.string() << "/{frames,table2,"
              << "figure6,pairs,meta}.csv\n";
  } catch (const std::exception& e) {
    std::cerr << "\nenhanced_orb_evaluate: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
