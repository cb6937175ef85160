// Google Benchmark of every stage and of whole frames, side by side in one run: this project's
// default mode, paper preset and baseline at budgets 500, 1000, 2000 and every corner, on 1 and 2
// threads and at each instruction set, against cv::ORB at the same budgets on one thread, on the
// EuRoC frames (ENHANCED_ORB_EUROC_DIR or --frames DIR). Each frame benchmark also counts the heap
// allocations per frame (operator new and cv::Mat buffers) once its workspaces are warm.
//
//   devel/lib/enhanced_orb/benchmark_extraction [--frames DIR] [google benchmark options]
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "allocation_count.h"
#include "enhanced_orb/adaptive_threshold.h"
#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/enhance.h"
#include "enhanced_orb/evaluation/dataset.h"
#include "enhanced_orb/evaluation/files.h"
#include "enhanced_orb/orb_extractor.h"
#include "enhanced_orb/rbrief.h"
#include "enhanced_orb/simd.h"

namespace eo = enhanced_orb;
namespace fs = std::filesystem;

namespace {

// OpenCV's pool for one benchmark, back to one thread afterwards.
struct ThreadScope {
  explicit ThreadScope(int threads) { cv::setNumThreads(threads); }
  ~ThreadScope() { cv::setNumThreads(1); }
};

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

// Judging a stream's frames (CameraMotion::update), every other frame shifted by 6 pixels.
// The judgment alone. range(0) 0: the frames as recorded (a still camera: the frame against the last
// one and against the reference, two inverse DFTs); 1: alternately shifted by 6 px (a moving camera:
// each frame moves and is the next one's reference, one inverse DFT).
void BM_CameraMotion(benchmark::State& state) {
  const bool moving = state.range(0) == 1;
  std::vector<cv::Mat> stream;
  for (const cv::Mat& f : frames()) {
    if (moving) {
      stream.push_back(f(cv::Rect(6, 0, f.cols - 6, f.rows)).clone());
      stream.push_back(f(cv::Rect(0, 0, f.cols - 6, f.rows)).clone());
    } else {
      stream.push_back(f);
    }
  }
  eo::CameraMotion motion;
  size_t i = 0;
  for (; i < 3; ++i) {
    motion.update(stream[i % stream.size()]);
  }
  const long before = eo::bench::allocations();
  for (auto _ : state) {
    benchmark::DoNotOptimize(motion.update(stream[i++ % stream.size()]));
  }
  state.counters["allocs_per_frame"] =
      static_cast<double>(eo::bench::allocations() - before) / static_cast<double>(state.iterations());
  state.SetLabel(moving ? "moving camera: thumbnail, one DFT, one inverse DFT"
                        : "still camera: thumbnail, one DFT, two inverse DFTs");
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

// Stages, one thread unless said. range(0) of BM_Enhance: 0, 1 the paper preset's enhancement
// (gamma by the paper's test, or always), 2 the default mode's; range(1): threads.
void BM_Enhance(benchmark::State& state) {
  eo::EnhanceParams p = state.range(0) == 2 ? eo::EnhanceParams() : eo::Params::paper().enhance;
  if (state.range(0) == 1) {
    p.gamma_mode = eo::GammaMode::kAlways;
  }
  const int threads = static_cast<int>(state.range(1));
  p.threads = threads;
  ThreadScope scope(threads);
  FrameCycle cycle;
  cv::Mat out;
  eo::EnhanceWorkspace workspace;
  for (auto _ : state) {
    out = eo::enhance(cycle.next(), p, workspace, out).image;
    benchmark::DoNotOptimize(out.data);
  }
  static const char* labels[] = {"paper, gamma auto (EuRoC: not poor)", "paper, gamma always",
                                 "default mode (global edge-weighted curve, 8 bits)"};
  state.SetLabel(std::string(labels[state.range(0)]) + ", " + std::to_string(threads) + " thread(s)");
}

void BM_Pyramid(benchmark::State& state) {
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(eo::buildPyramid(stages()[i++ % stages().size()].enhanced, 8, 1.2).size());
  }
  state.SetLabel("8 levels, INTER_LINEAR_EXACT to the bit");
}

void BM_Thresholds(benchmark::State& state) {
  size_t i = 0;
  eo::ThresholdWorkspace ws;
  cv::Mat thresholds;
  for (auto _ : state) {
    for (const cv::Mat& level : stages()[i++ % stages().size()].pyramid) {
      eo::cellThresholds(level, eo::ThresholdParams(), ws, thresholds);
      benchmark::DoNotOptimize(thresholds.data);
    }
  }
  state.SetLabel("all 8 levels: histograms and 200 Otsu thresholds");
}

// range(0): 0 a fixed threshold of 20, 1 the adaptive thresholds; range(1): instruction set.
void BM_Fast(benchmark::State& state) {
  const bool adaptive = state.range(0) != 0;
  const eo::SimdLevel saved = eo::activeSimdLevel();
  const eo::SimdLevel simd = eo::setSimdLevel(static_cast<eo::SimdLevel>(state.range(1)));
  if (simd != static_cast<eo::SimdLevel>(state.range(1))) {
    eo::setSimdLevel(saved);
    state.SkipWithError("instruction set not supported here");
    return;
  }
  size_t i = 0;
  size_t corners = 0;
  eo::CornerWorkspace ws;
  std::vector<cv::KeyPoint> found;
  for (auto _ : state) {
    const Stages& s = stages()[i++ % stages().size()];
    for (size_t level = 0; level < s.pyramid.size(); ++level) {
      const cv::Mat fixed(s.thresholds[level].size(), CV_32S, cv::Scalar(20));
      eo::detectCorners(s.pyramid[level], adaptive ? s.thresholds[level] : fixed, ws, found);
      corners += found.size();
    }
  }
  eo::setSimdLevel(saved);
  state.counters["corners"] = benchmark::Counter(static_cast<double>(corners), benchmark::Counter::kAvgIterations);
  state.SetLabel(std::string(adaptive ? "adaptive thresholds" : "fixed 20") + ", enhanced image, " +
                 eo::toString(simd));
}

void BM_Orientation(benchmark::State& state) {
  size_t i = 0;
  std::vector<cv::KeyPoint> kps;
  for (auto _ : state) {
    const Stages& s = stages()[i++ % stages().size()];
    for (size_t level = 0; level < s.pyramid.size(); ++level) {
      kps = s.corners[level];
      eo::computeOrientation(s.pyramid[level], kps);
      benchmark::DoNotOptimize(kps.data());
    }
  }
  state.SetLabel("every adaptive corner");
}

// range(0): 0 this project's smoothing and rBRIEF, 1 cv::ORB::compute level by level.
void BM_Descriptors(benchmark::State& state) {
  const bool opencv = state.range(0) == 1;
  const cv::Ptr<cv::ORB> orb = cv::ORB::create(500, 1.2f, 1, eo::kEdgeThreshold, 0, 2, cv::ORB::HARRIS_SCORE, 31);
  size_t i = 0;
  eo::SmoothingBuffers buffers;
  cv::Mat smoothed, d;
  std::vector<cv::KeyPoint> kps;
  for (auto _ : state) {
    const Stages& s = stages()[i++ % stages().size()];
    for (size_t level = 0; level < s.pyramid.size(); ++level) {
      kps = s.corners[level];
      if (opencv) {
        orb->compute(s.pyramid[level], kps, d);
      } else {
        eo::smoothForDescription(s.pyramid[level], buffers, smoothed);
        d.create(static_cast<int>(kps.size()), eo::kDescriptorBytes, CV_8U);
        eo::describe(smoothed, kps, d, 0);
      }
      benchmark::DoNotOptimize(d.data);
    }
  }
  state.SetLabel(opencv ? "every adaptive corner, cv::ORB::compute per level"
                        : "every adaptive corner, smoothing + own rBRIEF");
}

enum Method { kBaseline = 0, kPaper = 1, kOpenCv = 2, kDefault = 3, kDefaultMoving = 4 };

// Whole frames. range(0): method; range(1): budget (0 = every corner); range(2): threads;
// range(3): instruction set (this project only).
void BM_Frame(benchmark::State& state) {
  const int method = static_cast<int>(state.range(0));
  const int budget = static_cast<int>(state.range(1));
  const int threads = static_cast<int>(state.range(2));
  const eo::SimdLevel saved = eo::activeSimdLevel();
  const eo::SimdLevel simd = eo::setSimdLevel(static_cast<eo::SimdLevel>(state.range(3)));
  if (method != kOpenCv && simd != static_cast<eo::SimdLevel>(state.range(3))) {
    eo::setSimdLevel(saved);
    state.SkipWithError("instruction set not supported here");
    return;
  }
  ThreadScope scope(threads);
  FrameCycle cycle;
  size_t keypoints = 0;
  long allocations = 0;
  if (method == kOpenCv) {
    // cv::ORB keeps at most nfeatures; "every corner" asks for more than any frame has.
    const cv::Ptr<cv::ORB> orb = cv::ORB::create(budget > 0 ? budget : 1000000, 1.2f, 8);
    std::vector<cv::KeyPoint> kps;
    cv::Mat d;
    for (size_t warm = 0; warm < frames().size(); ++warm) {
      orb->detectAndCompute(cycle.next(), cv::noArray(), kps, d);
    }
    const long before = eo::bench::allocations();
    for (auto _ : state) {
      orb->detectAndCompute(cycle.next(), cv::noArray(), kps, d);
      keypoints += kps.size();
    }
    allocations = eo::bench::allocations() - before;
  } else {
    const bool stream = method == kDefault || method == kDefaultMoving;
    eo::Params p = method == kPaper ? eo::Params::paper() : stream ? eo::Params() : eo::Params::baseline();
    p.orb.max_features = budget;
    p.orb.threads = threads;
    p.enhance.threads = threads;
    // The default mode as a camera's stream runs it: each frame judged (CameraMotion; the static
    // EuRoC frames are judged still) and extracted in one call; kDefaultMoving extracts as for a
    // moving camera (the judgment still runs: it gives the stream's lambda).
    if (method == kDefaultMoving) {
      p.orb.camera_motion = eo::MotionMode::kMoving;
    }
    const eo::OrbExtractor extractor(p);
    eo::CameraMotion motion;
    eo::ExtractOptions options;
    eo::Extraction out;
    auto run = [&](const cv::Mat& gray) {
      if (stream) {
        extractor.extract(gray, motion, options, out);
      } else {
        extractor.extract(gray, options, out);
      }
    };
    // One pass over the frames first: the workspaces reach the sizes these frames need, and the
    // allocations counted are those of a stream that has run for a while.
    for (size_t warm = 0; warm < frames().size(); ++warm) {
      run(cycle.next());
    }
    const long before = eo::bench::allocations();
    for (auto _ : state) {
      run(cycle.next());
      keypoints += out.keypoints.size();
    }
    allocations = eo::bench::allocations() - before;
  }
  eo::setSimdLevel(saved);
  const double iterations = static_cast<double>(state.iterations());
  state.counters["keypoints"] = static_cast<double>(keypoints) / iterations;
  state.counters["allocs_per_frame"] = static_cast<double>(allocations) / iterations;
  static const char* names[] = {"baseline ORB", "paper preset", "cv::ORB", "default mode",
                                "default mode, camera moving"};
  state.SetLabel(std::string(names[method]) + ", " + (budget ? std::to_string(budget) + " features" : "every corner") +
                 ", " + std::to_string(threads) + " thread(s)" +
                 (method == kOpenCv ? std::string() : std::string(", ") + eo::toString(simd)));
}

void frameArguments(benchmark::internal::Benchmark* b) {
  const int best = static_cast<int>(eo::supportedSimdLevels().back());
  for (int budget : {500, 1000, 2000, 0}) {
    b->Args({kOpenCv, budget, 1, best});
    for (int method : {kDefault, kDefaultMoving, kBaseline, kPaper}) {
      for (int threads : {1, 2}) {
        b->Args({method, budget, threads, best});
      }
    }
  }
  // Each instruction set below the best (the scalar kernels are references, not a path), at 1000.
  for (int simd = static_cast<int>(eo::SimdLevel::kVector128); simd < best; ++simd) {
    for (int method : {kDefault, kBaseline}) {
      b->Args({method, 1000, 1, simd});
    }
  }
}

BENCHMARK(BM_GrayFromBGR)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_CameraMotion)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Enhance)->ArgsProduct({{0, 1, 2}, {1, 2}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Pyramid)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Thresholds)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Fast)->ArgsProduct({{0, 1}, {1, 2}})->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Orientation)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Descriptors)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Frame)
    ->Apply(frameArguments)
    ->ArgNames({"method", "budget", "threads", "simd"})
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
    cv::Mat gray = enhanced_orb::evaluation::readGrayChecked(ref.path, enhanced_orb::kMaxImagePixels, error);
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
  const eo::bench::MatBufferCount mat_buffers;
  cv::setNumThreads(1);  // single-threaded unless a benchmark says otherwise, every method alike
  stages();              // prepared before timing starts
  benchmark::AddCustomContext("simd", eo::toString(eo::activeSimdLevel()));
  benchmark::AddCustomContext("frames", std::to_string(frames().size()) + " x " + std::to_string(frames()[0].cols) +
                                            "x" + std::to_string(frames()[0].rows) + " from " + dir);
  int n = static_cast<int>(args.size());
  benchmark::Initialize(&n, args.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
