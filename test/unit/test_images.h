// Images shared by the unit tests: a deterministic synthetic scene and the EuRoC frames.
#ifndef ENHANCED_ORB_TEST_IMAGES_H
#define ENHANCED_ORB_TEST_IMAGES_H

#include <algorithm>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "shared_data.h"

namespace enhanced_orb {
namespace test {

// A gray scene of random filled rectangles and circles: plenty of corners at every scale.
inline cv::Mat syntheticScene(cv::Size size = cv::Size(640, 480), int shapes = 150, std::uint64_t seed = 7) {
  cv::RNG rng(seed);
  cv::Mat image(size, CV_8UC1, cv::Scalar(110));
  for (int i = 0; i < shapes; ++i) {
    const cv::Point p(rng.uniform(0, size.width), rng.uniform(0, size.height));
    const int extent = rng.uniform(8, 60);
    const cv::Scalar value(rng.uniform(0, 256));
    if (i % 2 == 0) {
      cv::rectangle(image, cv::Rect(p, cv::Size(extent, rng.uniform(8, 60))), value, cv::FILLED);
    } else {
      cv::circle(image, p, extent / 2, value, cv::FILLED);
    }
  }
  return image;
}

// Folder of the shared EuRoC V1_01_easy excerpt (set by CMake).
inline std::string eurocDir() {
  return ENHANCED_ORB_EUROC_DIR;
}

// The first cam0 frame of the excerpt, or an empty Mat when ../shared is absent.
inline cv::Mat eurocFrame(const std::string& name = "1403715273262142976.png") {
  return cv::imread(eurocDir() + "/mav0/cam0/data/" + name, cv::IMREAD_GRAYSCALE);
}

// Every `stride`-th of the first `count` cam0 frames of a EuRoC ASL folder, sorted by name; empty
// when the folder is absent.
inline std::vector<cv::Mat> cam0Frames(const std::string& dir, size_t stride = 1, size_t count = SIZE_MAX) {
  std::vector<std::string> names;
  const std::filesystem::path data = dir + "/mav0/cam0/data";
  if (std::filesystem::is_directory(data)) {
    for (const auto& entry : std::filesystem::directory_iterator(data)) {
      if (entry.path().extension() == ".png") {
        names.push_back(entry.path().string());
      }
    }
  }
  std::sort(names.begin(), names.end());
  std::vector<cv::Mat> frames;
  for (size_t i = 0; i < std::min(count, names.size()); i += std::max<size_t>(1, stride)) {
    frames.push_back(cv::imread(names[i], cv::IMREAD_GRAYSCALE));
  }
  return frames;
}

}  // namespace test
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_TEST_IMAGES_H
