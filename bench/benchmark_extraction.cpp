// Google Benchmark of every stage and of whole frames: baseline ORB, enhanced ORB and cv::ORB at
// equal budgets, single-threaded, on the EuRoC frames (ENHANCED_ORB_EUROC_DIR or --frames DIR).
//
//   devel/lib/enhanced_orb/benchmark_extraction [--frames DIR] [google benchmark options]
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/adaptive_threshold.h"
#include "enhanced_orb/enhance.h"
#include "enhanced_orb/evaluation/dataset.h"
#include "enhanced_orb/evaluation/files.h"
#include "enhanced_orb/orb_extractor.h"

namespace eo = enhanced_orb;
namespace fs = std::filesystem;

namespace {

std::vector<cv::Mat>& frames() {
  static std::vector<cv::Mat> images;
  return images;
}

const cv::Mat& frame(size_t i) {
  return frames()[i % frames().size()];
}

// Every stage runs on the frames in turn, one frame per iteration.
struct FrameCycle {
  size_t i = 0;
  const cv::Mat& next() { return frame(i++); }
};

// The paper preset (the paper's tables measure it) and the default mode, at a budget.
eo::Params improved(int max_features) {
  eo::Params p = eo::Params::paper();
  p.orb.max_features = max_features;
  return p;
}

eo::Params defaultMode(int max_features) {
  eo::Params p;
  p.orb.max_features = max_features;
  return p;
}

eo::Params baseline(int max_features) {
  eo::Params p = eo::Params::baseline();
  p.orb.max_features = max_features;
  return p;
}

// Intermediate results of one frame, so that each stage can be timed on its own input.
struct Stages {
  cv::Mat enhanced;
  std::vector<cv::Mat> pyramid;
  std::vector<cv::Mat> thresholds;
  std::vector<std::vector<cv::KeyPoint>> corners;
};

const std::vector<Stages>& stages() {
  static std::vector<Stages> all = [] {
    std::vector<Stages> out;
    for (const cv::Mat& f : frames()) {
      Stages s;
      s.enhanced = eo::enhance(f, eo::EnhanceParams()).image;
      s.pyramid = eo::buildPyramid(s.enhanced, 8, 1.2);
      for (const cv::Mat& level : s.pyramid) {
        s.thresholds.push_back(eo::cellThresholds(level, eo::ThresholdParams()));
        s.corners.push_back(eo::detectCorners(level, s.thresholds.back()));
        eo::computeOrientation(level, s.corners.back());
      }
      out.push_back(std::move(s));
    }
    return out;
  }();
  return all;
}

void BM_GrayFromBGR(benchmark::State& state) {
  std::vector<cv::Mat> bgr;
  for (const cv::Mat& f : frames()) {
    cv::Mat c;
    cv::cvtColor(f, c, cv::COLOR_GRAY2BGR);
    bgr.push_back(c);
  }
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(eo::toGray(bgr[i++ % bgr.size()], eo::PixelFormat::kBGR).data);
  }
}

void BM_Enhance(benchmark::State& state) {
  // 0, 1: the paper preset's enhancement, gamma by the paper's test or always; 2: the default mode's.
  eo::EnhanceParams p = state.range(0) == 2 ? eo::EnhanceParams() : eo::Params::paper().enhance;
  if (state.range(0) == 1) {
    p.gamma_mode = eo::GammaMode::kAlways;
  }
  FrameCycle cycle;
  for (auto _ : state) {
    benchmark::DoNotOptimize(eo::enhance(cycle.next(), p).image.data);
  }
  static const char* labels[] = {"paper, gamma auto (EuRoC: not poor)", "paper, gamma always",
                                 "default mode (tiled equalisation)"};
  state.SetLabel(labels[state.range(0)]);
}

void BM_Pyramid(benchmark::State& state) {
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(eo::buildPyramid(stages()[i++ % stages().size()].enhanced, 8, 1.2).size());
  }
}

void BM_Thresholds(benchmark::State& state) {
  size_t i = 0;
  for (auto _ : state) {
    for (const cv::Mat& level : stages()[i++ % stages().size()].pyramid) {
      benchmark::DoNotOptimize(eo::cellThresholds(level, eo::ThresholdParams()).data);
    }
  }
  state.SetLabel("all 8 levels");
}

void BM_Fast(benchmark::State& state) {
  const bool adaptive = state.range(0) != 0;
  size_t i = 0;
  size_t corners = 0;
  for (auto _ : state) {
    const Stages& s = stages()[i++ % stages().size()];
    for (size_t level = 0; level < s.pyramid.size(); ++level) {
      const cv::Mat fixed(s.thresholds[level].size(), CV_32S, cv::Scalar(20));
      corners += eo::detectCorners(s.pyramid[level], adaptive ? s.thresholds[level] : fixed).size();
    }
  }
  state.counters["corners"] = benchmark::Counter(static_cast<double>(corners), benchmark::Counter::kAvgIterations);
  state.SetLabel(adaptive ? "adaptive thresholds, enhanced image" : "fixed 20, enhanced image");
}

void BM_Orientation(benchmark::State& state) {
  size_t i = 0;
  for (auto _ : state) {
    const Stages& s = stages()[i++ % stages().size()];
    for (size_t level = 0; level < s.pyramid.size(); ++level) {
      std::vector<cv::KeyPoint> kps = s.corners[level];
      eo::computeOrientation(s.pyramid[level], kps);
      benchmark::DoNotOptimize(kps.data());
    }
  }
  state.SetLabel("every adaptive corner");
}

void BM_Descriptors(benchmark::State& state) {
  const cv::Ptr<cv::ORB> orb = cv::ORB::create(500, 1.2f, 1, eo::kEdgeThreshold, 0, 2, cv::ORB::HARRIS_SCORE, 31);
  size_t i = 0;
  for (auto _ : state) {
    const Stages& s = stages()[i++ % stages().size()];
    for (size_t level = 0; level < s.pyramid.size(); ++level) {
      std::vector<cv::KeyPoint> kps = s.corners[level];
      cv::Mat d;
      orb->compute(s.pyramid[level], kps, d);
      benchmark::DoNotOptimize(d.data);
    }
  }
  state.SetLabel("every adaptive corner (cv::ORB per level)");
}

// Whole frames. range(0): 0 baseline, 1 paper preset, 2 cv::ORB, 3 default mode; range(1): budget
// (0 = unlimited).
void BM_Frame(benchmark::State& state) {
  const int method = static_cast<int>(state.range(0));
  const int budget = static_cast<int>(state.range(1));
  FrameCycle cycle;
  size_t keypoints = 0;
  if (method == 2) {
    // cv::ORB keeps at most nfeatures; "unlimited" asks for more than any frame has.
    const cv::Ptr<cv::ORB> orb = cv::ORB::create(budget > 0 ? budget : 1000000, 1.2f, 8);
    for (auto _ : state) {
      std::vector<cv::KeyPoint> kps;
      cv::Mat d;
      orb->detectAndCompute(cycle.next(), cv::noArray(), kps, d);
      keypoints += kps.size();
    }
  } else {
    const eo::OrbExtractor extractor(method == 1   ? improved(budget)
                                     : method == 3 ? defaultMode(budget)
                                                   : baseline(budget));
    for (auto _ : state) {
      keypoints += extractor.extract(cycle.next()).keypoints.size();
    }
  }
  state.counters["keypoints"] = benchmark::Counter(static_cast<double>(keypoints), benchmark::Counter::kAvgIterations);
  static const char* names[] = {"baseline ORB", "paper preset", "cv::ORB", "default mode"};
  state.SetLabel(std::string(names[method]) + (budget ? ", 1000 features" : ", unlimited"));
}

BENCHMARK(BM_GrayFromBGR)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Enhance)->Arg(0)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Pyramid)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Thresholds)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Fast)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Orientation)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Descriptors)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Frame)
    ->ArgsProduct({{0, 1, 2, 3}, {0, 1000}})
    ->ArgNames({"method", "budget"})
    ->Unit(benchmark::kMillisecond);

}  // namespace

int main(int argc, char** argv) {
  std::string dir = ENHANCED_ORB_EUROC_DIR "/mav0/cam0/data";
  std::vector<char*> args{argv[0]};
  for (int i = 1; i < argc; ++i) {
    if (std::string(argv[i]) == "--frames" && i + 1 < argc) {
      dir = argv[++i];
    } else {
      args.push_back(argv[i]);
    }
  }
  if (!fs::is_directory(dir)) {
    std::cerr << "benchmark_extraction: no frames at " << dir << " (give --frames DIR)\n";
    return 1;
  }
  for (const enhanced_orb::evaluation::FrameRef& ref : enhanced_orb::evaluation::readImageFolder(dir)) {
    std::string error;
    cv::Mat gray = enhanced_orb::evaluation::readGrayChecked(ref.path, enhanced_orb::evaluation::kMaxPixels, error);
    if (gray.empty()) {
      std::cerr << "benchmark_extraction: skipped " << error << "\n";
    } else {
      frames().push_back(gray);
    }
  }
  if (frames().empty()) {
    std::cerr << "benchmark_extraction: no readable image in " << dir << "\n";
    return 1;
  }
  cv::setNumThreads(1);  // single-threaded, every method alike
  stages();              // prepared before timing starts
  benchmark::AddCustomContext("frames", std::to_string(frames().size()) + " x " + std::to_string(frames()[0].cols) +
                                            "x" + std::to_string(frames()[0].rows) + " from " + dir);
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
