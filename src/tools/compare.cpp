// enhanced_orb_compare: every method at equal budgets under real and modelled lighting change, and
// (--paper) the paper's own experiments. Writes CSV files that scripts/report.py turns into the
// tables and plots of docs/RESULTS.md.
#include <algorithm>
#include <atomic>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>

#include "enhanced_orb/evaluation/dataset.h"
#include "enhanced_orb/evaluation/degrade.h"
#include "enhanced_orb/evaluation/files.h"
#include "enhanced_orb/evaluation/methods.h"
#include "enhanced_orb/evaluation/metrics.h"
#include "enhanced_orb/evaluation/sequence.h"
#include "paper_experiments.h"
#include "progress.h"

namespace fs = std::filesystem;
namespace ev = enhanced_orb::evaluation;
using enhanced_orb::tools::progress;

namespace {

const char* const kUsage = R"(usage: enhanced_orb_compare [--lighting DIR] [--euroc DIR] [--sequence DIR] [options]
       enhanced_orb_compare --paper (--euroc DIR | --images DIR | --bag FILE --topic T) [options]

Compares the extractors at equal budgets (matching: mutual Hamming nearest neighbours).
  --lighting DIR     a folder of image-pair sets (each subfolder with a pairs.csv): correct
                     matches within 3 px (4 px for a set named webcam) and repeatability
  --euroc DIR        a EuRoC sequence: each frame against its degraded copies (identity ground
                     truth), and frame pairs with both frames degraded alike (epipolar ground
                     truth within 3 px; relative pose from the matches by RANSAC on E)
  --sequence DIR     a moving sequence with ground-truth poses (EuRoC ASL folder, or KITTI odometry
                     folder with image_0, calib.txt, poses.txt) under light that changes frame by
                     frame: relative pose between frames t and t + gap (AUC at 5/10/20 degrees)
                     and, with a second camera, stereo frame-to-frame tracking by PnP. Each
                     camera's frames are a stream, judged in order (camera_motion auto), as a
                     nodelet or an adapter judges them; --lighting and --euroc compare single
                     images (a stream's first frame: judged still)
  --paper            instead: the paper's experiments (ALGORITHM.md section 4: its original ORB,
                     its improved ORB = the paper preset, cv::ORB; budgets 0 = every corner and
                     1000) on the frames of --euroc DIR (pairs judged by its poses), --images DIR
                     (every .png/.jpg/.pgm in name order) or --bag FILE --topic T; writes
                     frames.csv, table2.csv, figure6.csv, pairs.csv, meta.csv for
                     scripts/report.py paper. Its defaults: --budgets 0,1000 --every 10
                     --pair-every 5 (photometric changes and pairs); --max-frames N uses N frames
options:
  --output DIR       where to write lighting.csv, euroc_photometric.csv, euroc_pairs.csv,
                     sequence_pose.csv, sequence_tracking.csv, sequence_light.csv
                     (default: results/compare)
  --budgets LIST     feature budgets (default 500,1000,2000)
  --methods LIST     of default,motion,stretch,paper,baseline,cv::ORB,CLAHE+cv::ORB,ORB-SLAM
                     (default: all)
  --set NAME=VALUE   a parameter of the default mode (repeatable; e.g. --set alpha=0.7)
  --label NAME       the default mode's name in the output (default: default)
  --degradations L   EuRoC degradations (default: all of none,lowlight,lowlight_gain,spotlight,
                     gradient,dark,bright,gamma_0.5,gamma_2,noise_10)
  --every N          EuRoC frames compared with their degraded copies: every N-th (default 5)
  --steps LIST       EuRoC frame pairs K frames apart (default 1,5,10)
  --pair-every N     a frame pair starts every N-th frame (default 3)
  --stereo-every N   the stereo pose test at every N-th frame (default 1: each frame has its own
                     noise, so more pairs average the pose error over more of it)
  --conditions LIST  --sequence light conditions (default: all of unchanged,dim,dark,dusk,
                     lights_out,flicker,lamp,dip)
  --gaps LIST        --sequence frame gaps (default 1,5,10 at 20 Hz; 1,3,5 at 10 Hz)
  --sequence-every N --sequence: a relative-pose pair starts at every N-th frame (default 1)
  --poses FILE       --sequence on KITTI: the poses file (default DIR/poses.txt)
  --pose-draws N     each relative pose (--euroc pairs, --sequence) estimated N times, the RANSAC
                     drawing other samples each time (the matches shuffled), and the median error
                     kept: less of one RANSAC's luck in an AUC (default 1: one draw, the tables')
  --write-sequence OUT  with --sequence (EuRoC): instead of comparing, write the frames of each
                     light condition as a EuRoC folder OUT/<condition> (and OUT/<condition>/times.txt),
                     the frames the comparison sees, for a SLAM system to run on
  --threads N        worker threads (default 2; each extraction itself runs on one)
  -h, --help         this text
Exit codes: 0 done, 1 an input could not be read, 2 bad arguments.
)";

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    if (!item.empty()) {
      out.push_back(item);
    }
  }
  return out;
}

bool parsePositive(const std::string& text, int& out) {
  std::istringstream in(text);
  int v = 0;
  in >> v;
  if (in.fail() || !in.eof() || v < 0) {
    return false;
  }
  out = v;
  return true;
}

struct Options {
  std::string lighting, euroc, sequence, poses, write_sequence, output = "results/compare", label = "default";
  bool paper = false;
  std::string images, bag, topic;
  int max_frames = 0;
  std::vector<std::string> given;  // the options given
  std::vector<std::string> conditions;
  std::vector<int> gaps;
  int sequence_every = 1;
  std::vector<int> budgets{500, 1000, 2000};
  std::vector<std::string> methods = ev::methodNames();
  std::vector<std::string> degradations;
  enhanced_orb::Params params;
  int every = 5, pair_every = 3, stereo_every = 1, threads = 2, pose_draws = 1;
  std::vector<int> steps{1, 5, 10};
};

// Runs body(i) for i in [0, n) on `threads` workers; each worker gets its own copy of the methods.
template <typename Body>
void parallelFor(int n, int threads, Body body) {
  std::atomic<int> next{0};
  std::vector<std::thread> pool;
  for (int w = 0; w < std::max(1, threads); ++w) {
    pool.emplace_back([&, w] {
      for (int i = next++; i < n; i = next++) {
        body(w, i);
      }
    });
  }
  for (std::thread& t : pool) {
    t.join();
  }
}

// One method (one name and budget) with a private instance per worker thread.
struct Runner {
  std::string label;
  int budget;
  std::vector<ev::Method> per_worker;
  ev::Features run(int worker, const cv::Mat& gray, const enhanced_orb::StreamJudgment& stream = {}) const {
    return per_worker[worker].run(gray, stream);
  }
};

std::vector<Runner> runners(const Options& o) {
  std::vector<Runner> out;
  for (int budget : o.budgets) {
    for (const std::string& name : o.methods) {
      Runner r{name == "default" ? o.label : name, budget, {}};
      for (int w = 0; w < o.threads; ++w) {
        r.per_worker.push_back(ev::makeMethod(name, budget, o.params));
      }
      out.push_back(std::move(r));
    }
  }
  return out;
}

void compareLighting(const Options& o, const std::vector<Runner>& all) {
  std::vector<ev::ImagePair> pairs;
  std::vector<fs::path> sets;
  for (const auto& entry : fs::directory_iterator(o.lighting)) {
    if (fs::is_regular_file(entry.path() / "pairs.csv")) {
      sets.push_back(entry.path());
    }
  }
  std::sort(sets.begin(), sets.end());
  for (const fs::path& set : sets) {
    for (ev::ImagePair& p : ev::readPairs(set.string())) {
      pairs.push_back(std::move(p));
    }
  }
  ev::AtomicTextFile csv_file((fs::path(o.output) / "lighting.csv").string());  // renamed when complete
  std::ostream& csv = csv_file.out();
  csv << "set,sequence,target,mean_target,method,budget,keypoints_ref,keypoints_target,matches,correct,"
         "repeatability\n";
  std::vector<std::string> rows(pairs.size() * all.size());
  std::map<std::string, cv::Mat> images;  // decoded once
  for (const ev::ImagePair& p : pairs) {
    for (const std::string& path : {p.reference, p.target}) {
      if (!images.count(path)) {
        images[path] = ev::readGray(path);
      }
    }
  }
  std::atomic<int> done{0};
  const int n = static_cast<int>(pairs.size());
  parallelFor(n, o.threads, [&](int w, int i) {
    const ev::ImagePair& p = pairs[i];
    const cv::Mat& ref = images.at(p.reference);
    const cv::Mat& target = images.at(p.target);
    const double tolerance = p.set == "webcam" ? 4.0 : 3.0;
    for (size_t m = 0; m < all.size(); ++m) {
      std::ostringstream row;
      row << p.set << "," << p.sequence << "," << fs::path(p.target).filename().string() << "," << p.mean_target << ","
          << all[m].label << "," << all[m].budget << ",";
      if (ref.empty() || target.empty()) {
        row << "0,0,0,0,0\n";
      } else {
        const ev::Features a = all[m].run(w, ref);
        const ev::Features b = all[m].run(w, target);
        const ev::MatchCounts c =
            ev::matchAndCount(a.keypoints, a.descriptors, b.keypoints, b.descriptors, ev::identity(tolerance));
        row << a.keypoints.size() << "," << b.keypoints.size() << "," << c.matches << "," << c.correct << ","
            << ev::repeatability(a.keypoints, b.keypoints, tolerance) << "\n";
      }
      rows[static_cast<size_t>(i) * all.size() + m] = row.str();
    }
    if (w == 0) {
      progress("lighting pairs", done, n);
    }
    ++done;
  });
  progress("lighting pairs", n, n);
  for (const std::string& r : rows) {
    csv << r;
  }
  csv_file.commit();
}

// Each sampled frame against its degraded copies (identity ground truth), one CSV row each.
template <typename At>
void writePhotometric(const Options& o, const Runner& method, const std::vector<ev::Degradation>& degradations,
                      int n_frames, At at, std::ostream& photometric) {
  const int n_deg = static_cast<int>(degradations.size());
  const int none = static_cast<int>(std::find_if(degradations.begin(), degradations.end(),
                                                 [](const ev::Degradation& d) { return d.name == "none"; }) -
                                    degradations.begin());
  for (int i = 0; i < n_frames && none < n_deg; i += o.every) {
    for (int d = 0; d < n_deg; ++d) {
      if (d == none) {
        continue;
      }
      const ev::Features& a = at(i, none);
      const ev::Features& b = at(i, d);
      const ev::MatchCounts c =
          ev::matchAndCount(a.keypoints, a.descriptors, b.keypoints, b.descriptors, ev::identity(3.0));
      photometric << i << "," << degradations[d].name << "," << method.label << "," << method.budget << ","
                  << b.keypoints.size() << "," << c.matches << "," << c.correct << ","
                  << ev::repeatability(a.keypoints, b.keypoints) << "," << b.ms << "\n";
    }
  }
}

// EuRoC's pair tests: cam0 frame `first` against cam0 frame first + step (step > 0), or against cam1
// at the same time (step 0, the stereo pose test).
struct PairJob {
  int first, step;
  const cv::Mat* right = nullptr;
  ev::RelativePose truth;
  ev::GroundTruth correct;
  bool is_static = false;
};

std::vector<PairJob> pairJobs(const Options& o, const ev::EurocSequence& seq, const ev::EurocSequence& right,
                              const std::map<std::int64_t, cv::Mat>& right_frames) {
  std::vector<PairJob> jobs;
  const int n_frames = static_cast<int>(seq.frames.size());
  if (seq.camera && seq.trajectory) {
    const ev::Camera& cam0 = *seq.camera;
    for (int step : o.steps) {
      for (int i = 0; i + step < n_frames; i += o.pair_every) {
        const auto p1 = seq.trajectory->at(seq.frames[i].stamp);
        const auto p2 = seq.trajectory->at(seq.frames[i + step].stamp);
        if (p1 && p2) {
          PairJob job{i, step, nullptr, ev::groundTruthPose(cam0, *p1, cam0, *p2), {}, false};
          job.is_static = ev::isStatic(job.truth);
          job.correct = job.is_static ? ev::rotationOnly(cam0, cam0, job.truth) : ev::epipolar(cam0, *p1, *p2);
          jobs.push_back(job);
        }
      }
    }
    if (right.camera) {
      for (int i = 0; i < n_frames; i += o.stereo_every) {
        const auto pose = seq.trajectory->at(seq.frames[i].stamp);
        const auto it = right_frames.find(seq.frames[i].stamp);
        if (pose && it != right_frames.end() && !it->second.empty()) {
          jobs.push_back({i, 0, &it->second, ev::groundTruthPose(cam0, *pose, *right.camera, *pose),
                          ev::epipolar(cam0, *pose, *right.camera, *pose), false});
        }
      }
    }
  } else {
    std::cerr << "enhanced_orb_compare: " << o.euroc << " has no calibration or ground truth: frame pairs skipped\n";
  }
  return jobs;
}

void compareEuroc(const Options& o, const std::vector<Runner>& all) {
  const ev::EurocSequence seq = ev::readEuroc(o.euroc);
  std::vector<cv::Mat> frames;
  for (const ev::FrameRef& f : seq.frames) {
    frames.push_back(ev::readGray(f.path));
  }
  std::vector<ev::Degradation> degradations = ev::standardDegradations();
  if (!o.degradations.empty()) {
    degradations.clear();
    for (const std::string& d : o.degradations) {
      degradations.push_back({d});
    }
  }
  const int n_frames = static_cast<int>(frames.size());
  const int n_deg = static_cast<int>(degradations.size());
  // Degraded frames, made once: frame i under degradation d has noise seed 1000 d + i.
  std::vector<cv::Mat> degraded(static_cast<size_t>(n_frames) * n_deg);
  parallelFor(n_frames * n_deg, o.threads, [&](int, int k) {
    degraded[k] = degradations[k % n_deg].apply(frames[k / n_deg], 1000ULL * (k % n_deg) + k / n_deg);
  });

  // The second camera, for the stereo pose test: cam1 frames by timestamp.
  const ev::EurocSequence right = ev::readEuroc(o.euroc, "cam1");
  std::map<std::int64_t, cv::Mat> right_frames;
  for (const ev::FrameRef& f : right.frames) {
    right_frames[f.stamp] = ev::readGray(f.path);
  }

  const std::vector<PairJob> jobs = pairJobs(o, seq, right, right_frames);

  ev::AtomicTextFile photometric_file((fs::path(o.output) / "euroc_photometric.csv").string());
  std::ostream& photometric = photometric_file.out();
  photometric << "frame,degradation,method,budget,keypoints,matches,correct,repeatability,ms\n";
  ev::AtomicTextFile pairs_file((fs::path(o.output) / "euroc_pairs.csv").string());
  std::ostream& pair_csv = pairs_file.out();
  pair_csv << "frame,pair,static,degradation,method,budget,matches,correct,inliers,rotation_deg,translation_deg\n";
  for (size_t m = 0; m < all.size(); ++m) {
    const Runner& method = all[m];
    std::vector<ev::Features> features(degraded.size());
    parallelFor(static_cast<int>(degraded.size()), o.threads,
                [&](int w, int k) { features[k] = method.run(w, degraded[k]); });
    progress("EuRoC " + method.label + " " + std::to_string(method.budget), static_cast<int>(m) + 1,
             static_cast<int>(all.size()));
    auto at = [&](int frame, int d) -> const ev::Features& { return features[static_cast<size_t>(frame) * n_deg + d]; };
    writePhotometric(o, method, degradations, n_frames, at, photometric);
    std::vector<std::string> rows(jobs.size() * n_deg);
    parallelFor(static_cast<int>(rows.size()), o.threads, [&](int w, int k) {
      const PairJob& job = jobs[k / n_deg];
      const int d = k % n_deg;
      const ev::Features& a = at(job.first, d);
      const ev::Features b = job.right
                                 ? method.run(w, degradations[d].apply(*job.right, 7777ULL + 1000ULL * d + job.first))
                                 : at(job.first + job.step, d);
      const std::vector<cv::DMatch> matches = ev::mutualMatches(a.descriptors, b.descriptors);
      std::vector<cv::Point2f> p1, p2;
      int correct = 0;
      for (const cv::DMatch& mt : matches) {
        p1.push_back(a.keypoints[mt.queryIdx].pt);
        p2.push_back(b.keypoints[mt.trainIdx].pt);
        correct += job.correct(p1.back(), p2.back());
      }
      const ev::Camera& second = job.right ? *right.camera : *seq.camera;
      // A pose from a static pair is not defined: only stereo pairs and moving pairs are scored.
      const ev::DrawnPose drawn =
          job.is_static ? ev::DrawnPose() : ev::medianPoseOfDraws(*seq.camera, second, p1, p2, job.truth, o.pose_draws);
      const ev::PoseEstimate& pose = drawn.estimate;
      const ev::PoseError& error = drawn.error;
      std::ostringstream row;
      row << job.first << "," << (job.right ? std::string("stereo") : "+" + std::to_string(job.step)) << ","
          << job.is_static << "," << degradations[d].name << "," << method.label << "," << method.budget << ","
          << matches.size() << "," << correct << "," << pose.inliers << "," << error.rotation_deg << ","
          << error.translation_deg << "\n";
      rows[k] = row.str();
    });
    for (const std::string& r : rows) {
      pair_csv << r;
    }
  }
  photometric_file.commit();
  pairs_file.commit();
}

// The frames of a sequence, decoded once, and the light conditions asked for.
struct SequenceFrames {
  ev::Sequence seq;
  std::vector<ev::LightCondition> conditions;
  bool stereo = false;
  std::vector<cv::Mat> left, right;
  int size() const { return static_cast<int>(left.size()); }
};

SequenceFrames readSequenceFrames(const Options& o) {
  SequenceFrames f;
  f.seq = o.poses.empty() ? ev::readSequence(o.sequence) : ev::readKittiSequence(o.sequence, o.poses);
  const ev::Sequence& seq = f.seq;
  const int n = static_cast<int>(seq.frames.size());
  if (n < 2) {
    throw ev::DatasetError(o.sequence + ": fewer than two frames with a ground-truth pose");
  }
  f.conditions = ev::lightConditions();
  if (!o.conditions.empty()) {
    f.conditions.clear();
    for (const std::string& c : o.conditions) {
      f.conditions.push_back({c});
    }
  }
  f.stereo = seq.right.has_value() && !seq.right_frames.empty();
  f.left.resize(n);
  f.right.resize(f.stereo ? n : 0);
  parallelFor(n, o.threads, [&](int, int i) {
    f.left[i] = ev::readGray(seq.frames[i]);
    if (f.stereo) {
      f.right[i] = ev::readGray(seq.right_frames[i]);
    }
  });
  for (int i = 0; i < n; ++i) {
    if (f.left[i].empty() || (f.stereo && f.right[i].empty())) {
      throw ev::DatasetError((f.left[i].empty() ? seq.frames[i] : seq.right_frames[i]) + ": cannot be decoded");
    }
  }
  return f;
}

// Every frame under one light condition, each degraded once; the right camera has its own noise.
// Seeds follow the condition's name, so a run of some conditions repeats a full run's, and the
// frames --write-sequence writes are the ones the evaluation sees.
void degradeSequence(const SequenceFrames& f, const ev::LightCondition& light, int threads, std::vector<cv::Mat>& left,
                     std::vector<cv::Mat>& right) {
  std::uint64_t seed = 14695981039346656037ULL;  // FNV-1a of the name
  for (char ch : light.name) {
    seed = (seed ^ static_cast<unsigned char>(ch)) * 1099511628211ULL;
  }
  const int n = f.size();
  left.assign(n, cv::Mat());
  right.assign(f.stereo ? n : 0, cv::Mat());
  parallelFor(n, threads, [&](int, int i) {
    left[i] = light.apply(f.left[i], i, n, seed + 2ULL * i);
    if (f.stereo) {
      right[i] = light.apply(f.right[i], i, n, seed + 2ULL * i + 1);
    }
  });
}

// --write-sequence: each light condition as a EuRoC ASL folder of its own (OUT/<condition>/mav0 with
// cam0, cam1, their sensor.yaml and data.csv, and the ground truth) for a SLAM system to run on, and
// OUT/<condition>/times.txt: the frames' timestamps [ns], one per line, as ORB-SLAM's EuRoC examples
// read them.
void writeSequence(const Options& o) {
  const SequenceFrames f = readSequenceFrames(o);
  if (f.seq.format != "euroc") {
    throw ev::DatasetError(o.sequence + ": --write-sequence writes EuRoC folders, from a EuRoC sequence only");
  }
  const fs::path mav0 = fs::path(f.seq.frames[0]).parent_path().parent_path().parent_path();
  for (const ev::LightCondition& light : f.conditions) {
    std::vector<cv::Mat> dl, dr;
    degradeSequence(f, light, o.threads, dl, dr);
    const fs::path out = fs::path(o.write_sequence) / light.name;
    fs::create_directories(out);
    std::ofstream times(out / "times.txt");
    for (const std::string cam : {"cam0", "cam1"}) {
      const bool left = cam == "cam0";
      if (!left && !f.stereo) {
        continue;
      }
      const fs::path dir = out / "mav0" / cam;
      fs::create_directories(dir / "data");
      fs::copy_file(mav0 / cam / "sensor.yaml", dir / "sensor.yaml", fs::copy_options::overwrite_existing);
      std::ofstream csv(dir / "data.csv");
      csv << "#timestamp [ns],filename\n";
      for (int i = 0; i < f.size(); ++i) {
        const fs::path name = fs::path(left ? f.seq.frames[i] : f.seq.right_frames[i]).filename();
        if (!cv::imwrite((dir / "data" / name).string(), left ? dl[i] : dr[i])) {
          throw ev::DatasetError((dir / "data" / name).string() + ": cannot be written");
        }
        csv << name.stem().string() << "," << name.string() << "\n";
        if (left) {
          times << name.stem().string() << "\n";
        }
      }
    }
    fs::copy(mav0 / "state_groundtruth_estimate0", out / "mav0" / "state_groundtruth_estimate0",
             fs::copy_options::recursive | fs::copy_options::overwrite_existing);
    std::cerr << "wrote " << out.string() << " (" << f.size() << " frames)\n";
  }
}

// The relative-pose pairs of a sequence: frames t and t + gap for each gap, t every `every`-th frame;
// a pair whose camera barely moved is left out (its pose is not defined).
struct PosePair {
  int first, gap;
  ev::RelativePose truth;
};

std::vector<PosePair> posePairs(const ev::Sequence& seq, int n, const std::vector<int>& gaps, int every) {
  std::vector<PosePair> pairs;
  for (int g : gaps) {
    for (int i = 0; i + g < n; i += every) {
      const ev::RelativePose truth = ev::sequencePose(seq, i, i + g);
      if (!ev::isStatic(truth)) {
        pairs.push_back({i, g, truth});
      }
    }
  }
  return pairs;
}

// `text` as one CSV field: in double quotes, each quote doubled (RFC 4180).
std::string csvQuoted(const std::string& text) {
  std::string field = "\"";
  for (char ch : text) {
    field += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  }
  return field + "\"";
}

// One sequence_pose.csv row per pair: mutual matches, essential matrix (the median of pose_draws
// RANSAC draws), error against the truth.
std::vector<std::string> poseRows(const ev::Sequence& seq, const std::vector<PosePair>& pairs,
                                  const std::vector<ev::Features>& fl, const std::string& prefix, int pose_draws,
                                  int threads) {
  std::vector<std::string> rows(pairs.size());
  parallelFor(static_cast<int>(pairs.size()), threads, [&](int, int k) {
    const PosePair& p = pairs[k];
    const ev::Features& a = fl[p.first];
    const ev::Features& b = fl[p.first + p.gap];
    const std::vector<cv::DMatch> matches = ev::mutualMatches(a.descriptors, b.descriptors);
    std::vector<cv::Point2f> p1, p2;
    for (const cv::DMatch& mt : matches) {
      p1.push_back(a.keypoints[mt.queryIdx].pt);
      p2.push_back(b.keypoints[mt.trainIdx].pt);
    }
    const ev::DrawnPose drawn = ev::medianPoseOfDraws(seq.left, seq.left, p1, p2, p.truth, pose_draws);
    const ev::PoseEstimate& pose = drawn.estimate;
    const ev::PoseError& error = drawn.error;
    std::ostringstream row;
    row << prefix << "," << p.first << "," << p.gap << "," << a.keypoints.size() << "," << matches.size() << ","
        << pose.inliers << "," << error.rotation_deg << "," << error.translation_deg << "\n";
    rows[k] = row.str();
  });
  return rows;
}

// One sequence_tracking.csv row per frame t < n - 1: the stereo map of t tracked into t + 1.
std::vector<std::string> trackRows(const ev::Sequence& seq, const std::vector<ev::Features>& fl,
                                   const std::vector<ev::Features>& fr, const std::string& prefix, int threads) {
  const int n = static_cast<int>(fl.size());
  std::vector<std::string> rows(n - 1);
  parallelFor(n - 1, threads, [&](int, int i) {
    const ev::StereoMap map = ev::triangulateStereo(seq.left, *seq.right, fl[i].keypoints, fl[i].descriptors,
                                                    fr[i].keypoints, fr[i].descriptors);
    const ev::TrackResult t =
        ev::trackFrame(map, seq.left, fl[i + 1].keypoints, fl[i + 1].descriptors, ev::sequencePose(seq, i, i + 1));
    std::ostringstream row;
    row << prefix << "," << i << "," << map.points.size() << "," << t.matches << "," << t.inliers << "," << t.tracked()
        << "," << t.rotation_deg << "," << t.translation_m << "\n";
    rows[i] = row.str();
  });
  return rows;
}

// Real camera motion under light that changes frame by frame: every method on the same degraded
// frames (each frame degraded once per condition), relative pose between frames and stereo tracking.
void compareSequence(const Options& o, const std::vector<Runner>& all) {
  const SequenceFrames frames = readSequenceFrames(o);
  const ev::Sequence& seq = frames.seq;
  const std::vector<ev::LightCondition>& conditions = frames.conditions;
  const int n = frames.size();
  const bool stereo = frames.stereo;
  const std::vector<int> gaps = o.gaps.empty() ? ev::defaultGaps(seq.rate_hz) : o.gaps;
  std::cerr << "sequence " << seq.name << " (" << seq.format << "): " << n << " frames at " << seq.rate_hz << " Hz, "
            << (stereo ? "stereo" : "monocular") << ", gaps";
  for (int g : gaps) {
    std::cerr << " " << g;
  }
  std::cerr << "\n";
  const std::vector<PosePair> pairs = posePairs(seq, n, gaps, o.sequence_every);

  ev::AtomicTextFile pose_file((fs::path(o.output) / "sequence_pose.csv").string());
  std::ostream& pose_csv = pose_file.out();
  pose_csv << "sequence,condition,method,budget,frame,gap,keypoints,matches,inliers,rotation_deg,translation_deg\n";
  ev::AtomicTextFile track_file((fs::path(o.output) / "sequence_tracking.csv").string());
  std::ostream& track_csv = track_file.out();
  track_csv << "sequence,condition,method,budget,frame,map_points,matches,inliers,tracked,rotation_deg,"
               "translation_m\n";
  // What each condition does to these frames, for the report's legend.
  ev::AtomicTextFile light_file((fs::path(o.output) / "sequence_light.csv").string());
  light_file.out() << "sequence,condition,frames,description\n";
  for (const ev::LightCondition& light : conditions) {
    light_file.out() << seq.name << "," << light.name << "," << n << "," << csvQuoted(light.describe(n)) << "\n";
  }
  for (size_t c = 0; c < conditions.size(); ++c) {
    const ev::LightCondition& light = conditions[c];
    std::vector<cv::Mat> dl, dr;
    degradeSequence(frames, light, o.threads, dl, dr);
    // Each camera is a stream: its frames judged in order, as a nodelet or an adapter judges them.
    const std::vector<enhanced_orb::StreamJudgment> moving_l = ev::judgeMotion(dl), moving_r = ev::judgeMotion(dr);
    for (size_t m = 0; m < all.size(); ++m) {
      const Runner& method = all[m];
      std::vector<ev::Features> fl(n), fr(stereo ? n : 0);
      parallelFor(n, o.threads, [&](int w, int i) {
        fl[i] = method.run(w, dl[i], moving_l[i]);
        if (stereo) {
          fr[i] = method.run(w, dr[i], moving_r[i]);
        }
      });
      const std::string prefix = seq.name + "," + light.name + "," + method.label + "," + std::to_string(method.budget);
      const std::vector<std::string> pose_rows = poseRows(seq, pairs, fl, prefix, o.pose_draws, o.threads);
      for (const std::string& r : pose_rows) {
        pose_csv << r;
      }
      if (stereo) {
        const std::vector<std::string> track_rows = trackRows(seq, fl, fr, prefix, o.threads);
        for (const std::string& r : track_rows) {
          track_csv << r;
        }
      }
      progress("sequence " + light.name, static_cast<int>(c * all.size() + m) + 1,
               static_cast<int>(conditions.size() * all.size()));
    }
  }
  pose_file.commit();
  track_file.commit();
  light_file.commit();
}

// Reads one option and its value into `o`; false with `error` set when the value is not valid.
bool readOption(const std::string& arg, const std::string& v, Options& o, std::string& error) {
  bool ok = true;
  std::string* text = arg == "--lighting"         ? &o.lighting
                      : arg == "--euroc"          ? &o.euroc
                      : arg == "--sequence"       ? &o.sequence
                      : arg == "--write-sequence" ? &o.write_sequence
                      : arg == "--poses"          ? &o.poses
                      : arg == "--output"         ? &o.output
                      : arg == "--label"          ? &o.label
                      : arg == "--images"         ? &o.images
                      : arg == "--bag"            ? &o.bag
                      : arg == "--topic"          ? &o.topic
                                                  : nullptr;
  if (text) {
    *text = v;
  } else if (arg == "--conditions") {
    o.conditions = splitList(v);
    const std::vector<ev::LightCondition> known = ev::lightConditions();
    for (const std::string& c : o.conditions) {
      ok = ok && std::any_of(known.begin(), known.end(), [&](const ev::LightCondition& k) { return k.name == c; });
    }
    ok = ok && !o.conditions.empty();
  } else if (arg == "--methods") {
    o.methods = splitList(v);
  } else if (arg == "--degradations") {
    o.degradations = splitList(v);
  } else if (arg == "--set") {
    const size_t eq = v.find('=');
    error = eq == std::string::npos ? "expected NAME=VALUE"
                                    : enhanced_orb::setParam(o.params, v.substr(0, eq), v.substr(eq + 1));
    if (!error.empty()) {
      error = "--set " + v + ": " + error;
      return false;
    }
  } else if (arg == "--budgets" || arg == "--steps" || arg == "--gaps") {
    std::vector<int>& list = arg == "--budgets" ? o.budgets : arg == "--steps" ? o.steps : o.gaps;
    list.clear();
    for (const std::string& item : splitList(v)) {
      int n = 0;
      ok = ok && parsePositive(item, n);
      list.push_back(n);
    }
    ok = ok && !list.empty();
  } else if (arg == "--every" || arg == "--pair-every" || arg == "--stereo-every" || arg == "--threads" ||
             arg == "--sequence-every" || arg == "--max-frames" || arg == "--pose-draws") {
    int& target = arg == "--every"            ? o.every
                  : arg == "--pair-every"     ? o.pair_every
                  : arg == "--stereo-every"   ? o.stereo_every
                  : arg == "--sequence-every" ? o.sequence_every
                  : arg == "--max-frames"     ? o.max_frames
                  : arg == "--pose-draws"     ? o.pose_draws
                                              : o.threads;
    ok = parsePositive(v, target) && target > 0;
  } else {
    error = "unknown option " + arg;
    return false;
  }
  if (!ok) {
    error = "invalid value for " + arg + ": '" + v + "'";
  }
  o.given.push_back(arg);
  return ok;
}

bool given(const Options& o, const std::string& option) {
  return std::find(o.given.begin(), o.given.end(), option) != o.given.end();
}

// What is wrong with the options as a whole; empty when they make one run.
std::string checkOptions(const Options& o) {
  if (o.paper) {
    const int inputs = !o.euroc.empty() + !o.images.empty() + !o.bag.empty();
    if (inputs != 1 || (!o.bag.empty() && o.topic.empty()) || !o.lighting.empty() || !o.sequence.empty()) {
      return "--paper takes exactly one of --euroc DIR, --images DIR, --bag FILE --topic T";
    }
    return "";
  }
  for (const char* option : {"--images", "--bag", "--topic", "--max-frames"}) {
    if (given(o, option)) {
      return std::string(option) + " goes with --paper";
    }
  }
  if (o.lighting.empty() && o.euroc.empty() && o.sequence.empty()) {
    return "give --lighting DIR, --euroc DIR, --sequence DIR or several, or --paper";
  }
  const std::vector<std::string> problems = enhanced_orb::validate(o.params);
  if (!problems.empty()) {
    return enhanced_orb::joinMessages(problems);
  }
  if (!o.write_sequence.empty() && (o.sequence.empty() || !o.lighting.empty() || !o.euroc.empty())) {
    return "--write-sequence goes with --sequence alone";
  }
  return "";
}

int runPaper(const Options& o) {
  enhanced_orb::tools::PaperOptions p;
  p.euroc = o.euroc;
  p.images = o.images;
  p.bag = o.bag;
  p.topic = o.topic;
  p.output = given(o, "--output") ? o.output : "results";
  p.max_frames = o.max_frames;
  p.steps = o.steps;
  if (given(o, "--budgets")) {
    p.budgets = o.budgets;
  }
  if (given(o, "--every")) {
    p.every = o.every;
  }
  if (given(o, "--pair-every")) {
    p.pair_every = o.pair_every;
  }
  return enhanced_orb::tools::runPaperExperiments(p);
}

int run(const Options& o) {
  cv::setNumThreads(1);
  if (!o.write_sequence.empty()) {
    writeSequence(o);
    std::cout << "enhanced_orb_compare: wrote " << o.write_sequence << "\n";
    return 0;
  }
  const std::vector<Runner> all = runners(o);
  fs::create_directories(o.output);
  if (!o.lighting.empty()) {
    compareLighting(o, all);
  }
  if (!o.euroc.empty()) {
    compareEuroc(o, all);
  }
  if (!o.sequence.empty()) {
    compareSequence(o, all);
  }
  std::cout << "enhanced_orb_compare: wrote " << o.output << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      std::cout << kUsage;
      return 0;
    }
    if (arg == "--paper") {
      o.paper = true;
      continue;
    }
    if (i + 1 >= argc) {
      std::cerr << "enhanced_orb_compare: " << arg << " needs a value\n";
      return 2;
    }
    std::string error;
    if (!readOption(arg, argv[++i], o, error)) {
      std::cerr << "enhanced_orb_compare: " << error << "\n"
                << (error.rfind("unknown", 0) == 0 ? "\n" + std::string(kUsage) : "");
      return 2;
    }
  }
  const std::string problem = checkOptions(o);
  if (!problem.empty()) {
    std::cerr << "enhanced_orb_compare: " << problem << "\n\n" << kUsage;
    return 2;
  }
  try {
    return o.paper ? runPaper(o) : run(o);
  } catch (const std::exception& e) {
    std::cerr << "\nenhanced_orb_compare: " << e.what() << "\n";
    return 1;
  }
}
