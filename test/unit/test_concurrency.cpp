// The library's thread safety as the nodelets use it: one const OrbExtractor shared by several
// threads, and the extractor swapped whole under a mutex while others extract (reconfiguration).
#include <atomic>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "enhanced_orb/orb_extractor.h"
#include "parallel.h"
#include "test_images.h"

using namespace enhanced_orb;

// The library's parallel loop: every index runs once, the stripes see what the caller wrote before
// the call and the caller sees what they wrote. Under ThreadSanitizer (scripts/sanitize.sh thread)
// it also checks that the hand-off to OpenCV's pool is announced: without it, the stripes' first
// read of the caller's data is reported as a race.
TEST(Concurrency, ParallelLoopHandsOverTheCallersDataAndBack) {
  const int previous = cv::getNumThreads();
  cv::setNumThreads(4);
  std::vector<int> values(64);
  for (int round = 0; round < 20; ++round) {
    for (size_t k = 0; k < values.size(); ++k) {
      values[k] = round * 100 + static_cast<int>(k);
    }
    std::vector<int> runs(values.size(), 0);
    parallelFor(static_cast<int>(values.size()), [&](const cv::Range& range) {
      for (int k = range.start; k < range.end; ++k) {
        values[k] += 1;
        runs[k] += 1;
      }
    });
    for (size_t k = 0; k < values.size(); ++k) {
      ASSERT_EQ(runs[k], 1) << "index " << k << ", round " << round;
      ASSERT_EQ(values[k], round * 100 + static_cast<int>(k) + 1) << "index " << k << ", round " << round;
    }
  }
  cv::setNumThreads(previous);
}

// A stripe's exception reaches the caller as thrown, and only after every stripe has run.
TEST(Concurrency, ParallelLoopPassesAStripesExceptionOnAsThrown) {
  const int previous = cv::getNumThreads();
  cv::setNumThreads(4);
  std::vector<int> runs(16, 0);
  EXPECT_THROW(parallelFor(static_cast<int>(runs.size()),
                           [&](const cv::Range& range) {
                             for (int k = range.start; k < range.end; ++k) {
                               runs[k] += 1;
                               if (k == 5) {
                                 throw std::invalid_argument("stripe 5");
                               }
                             }
                           }),
               std::invalid_argument);
  for (size_t k = 0; k < runs.size(); ++k) {
    EXPECT_EQ(runs[k], 1) << "index " << k;
  }
  cv::setNumThreads(previous);
}

TEST(Concurrency, SharedExtractorGivesTheSequentialResults) {
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 4; ++i) {
    frames.push_back(test::syntheticScene(cv::Size(320, 240), 80, 100 + i));
  }
  const OrbExtractor extractor;
  std::vector<Extraction> expected;
  for (const cv::Mat& f : frames) {
    expected.push_back(extractor.extract(f));
  }
  std::atomic<int> mismatches{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t) {
    threads.emplace_back([&, t] {
      for (int round = 0; round < 10; ++round) {
        const size_t i = static_cast<size_t>(t + round) % frames.size();
        const Extraction r = extractor.extract(frames[i]);
        if (r.keypoints.size() != expected[i].keypoints.size() ||
            cv::norm(r.descriptors, expected[i].descriptors, cv::NORM_HAMMING) != 0.0 ||
            cv::norm(r.image, expected[i].image, cv::NORM_INF) != 0.0) {
          ++mismatches;
        }
      }
    });
  }
  for (auto& th : threads) {
    th.join();
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(Concurrency, SwappingTheExtractorWhileOthersExtract) {
  const cv::Mat frame = test::syntheticScene(cv::Size(320, 240));
  std::mutex mutex;
  std::shared_ptr<const OrbExtractor> current = std::make_shared<const OrbExtractor>();
  std::atomic<bool> stop{false};
  std::atomic<int> extractions{0};
  std::vector<std::thread> workers;
  for (int t = 0; t < 3; ++t) {
    workers.emplace_back([&] {
      while (!stop) {
        std::shared_ptr<const OrbExtractor> mine;
        {
          std::lock_guard<std::mutex> lock(mutex);
          mine = current;
        }
        const Extraction r = mine->extract(frame);
        EXPECT_EQ(r.descriptors.rows, static_cast<int>(r.keypoints.size()));
        ++extractions;
      }
    });
  }
  for (int c_min = 5; c_min < 60; c_min += 5) {
    Params p;
    p.threshold.c_min = c_min;
    auto next = std::make_shared<const OrbExtractor>(p);
    std::lock_guard<std::mutex> lock(mutex);
    current = next;
  }
  while (extractions < 30) {
    std::this_thread::yield();
  }
  stop = true;
  for (auto& th : workers) {
    th.join();
  }
  EXPECT_GE(extractions, 30);
}
