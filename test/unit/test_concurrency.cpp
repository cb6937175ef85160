// The library's thread safety as the nodelets use it: one const OrbExtractor shared by several
// threads, and the extractor swapped whole under a mutex while others extract (reconfiguration).
#include <atomic>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "enhanced_orb/orb_extractor.h"
#include "test_images.h"

using namespace enhanced_orb;

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
