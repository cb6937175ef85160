// Images shared by the unit tests: a deterministic synthetic scene and the EuRoC frames.
#ifndef ENHANCED_ORB_TEST_IMAGES_H
#define ENHANCED_ORB_TEST_IMAGES_H

#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

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

}  // namespace test
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_TEST_IMAGES_H
