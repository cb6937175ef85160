// What enhanced_orb::ORB gives on images taken in order as one stream, written with cv::FileStorage
// for the Python tests to compare with the Python module bit for bit:
//
//   python_test_reference OUT.yml PRESET NFEATURES IMAGE [IMAGE ...]
//
// For image i: kp_i (N x 7 CV_64F: x, y, size, angle, response, octave, class_id), desc_i (N x 32
// CV_8U) and moving_i (the selection the image got).
#include <iostream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "enhanced_orb/feature2d.h"
#include "enhanced_orb/params.h"

int main(int argc, char** argv) {
  if (argc < 5) {
    std::cerr << "usage: python_test_reference OUT.yml PRESET NFEATURES IMAGE [IMAGE ...]\n";
    return 2;
  }
  try {
    enhanced_orb::Params params = enhanced_orb::presetParams(argv[2]);
    params.orb.max_features = std::stoi(argv[3]);
    cv::Ptr<enhanced_orb::ORB> orb = enhanced_orb::ORB::create(params);
    cv::FileStorage fs(argv[1], cv::FileStorage::WRITE);
    for (int i = 4; i < argc; ++i) {
      const cv::Mat image = cv::imread(argv[i], cv::IMREAD_GRAYSCALE);
      if (image.empty()) {
        std::cerr << "python_test_reference: cannot read " << argv[i] << "\n";
        return 1;
      }
      std::vector<cv::KeyPoint> keypoints;
      cv::Mat descriptors;
      orb->detectAndCompute(image, cv::noArray(), keypoints, descriptors);
      cv::Mat rows(static_cast<int>(keypoints.size()), 7, CV_64F);
      for (int k = 0; k < rows.rows; ++k) {
        const cv::KeyPoint& p = keypoints[static_cast<size_t>(k)];
        const double row[7] = {p.pt.x, p.pt.y, p.size, p.angle, p.response, double(p.octave), double(p.class_id)};
        std::copy(row, row + 7, rows.ptr<double>(k));
      }
      const std::string n = std::to_string(i - 4);
      fs << "kp_" + n << rows << "desc_" + n << descriptors << "moving_" + n << int(orb->cameraMoving());
    }
  } catch (const std::exception& e) {
    std::cerr << "python_test_reference: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
