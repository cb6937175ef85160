// A program written for ORB-SLAM3's ORBextractor (what Frame and Tracking do with it), C++11 as
// ORB-SLAM builds; the type alias is all that changed. Checks the scale accessors, the lapping-area
// ordering and return value, and the image pyramid that ORB-SLAM's stereo matching reads after
// the call.
//   written_for_orb_slam IMAGE     exit 0 when every check holds, 1 otherwise
#include <cmath>
#include <vector>

#include <opencv2/core.hpp>

#include <enhanced_orb/orb_slam_extractor.h>

#include "checks.h"

// was: #include "ORBextractor.h" and ORB_SLAM3::ORBextractor
typedef enhanced_orb::OrbSlamExtractor ORBextractor;

using installed::check;

int main(int argc, char** argv) {
  const cv::Mat image = installed::frameFromArguments(argc, argv, "written_for_orb_slam");
  if (image.empty()) {
    return argc == 2 ? 1 : 2;
  }
  // Tracking::Tracking: nFeatures, scaleFactor, nLevels, iniThFAST, minThFAST from the settings.
  ORBextractor* extractor = new ORBextractor(1200, 1.2f, 8, 20, 7);

  // Frame::Frame: the scale tables.
  const int levels = extractor->GetLevels();
  const float scale = extractor->GetScaleFactor();
  const std::vector<float> factors = extractor->GetScaleFactors();
  const std::vector<float> inverse = extractor->GetInverseScaleFactors();
  const std::vector<float> sigma2 = extractor->GetScaleSigmaSquares();
  const std::vector<float> inverse_sigma2 = extractor->GetInverseScaleSigmaSquares();
  bool scales = levels == 8 && std::fabs(scale - 1.2f) < 1e-6f && factors.size() == 8u;
  for (int l = 0; scales && l < levels; ++l) {
    scales = std::fabs(factors[l] - std::pow(1.2f, static_cast<float>(l))) < 1e-4f &&
             std::fabs(inverse[l] * factors[l] - 1.f) < 1e-5f &&
             std::fabs(sigma2[l] - factors[l] * factors[l]) < 1e-3f &&
             std::fabs(inverse_sigma2[l] * sigma2[l] - 1.f) < 1e-5f;
  }
  check(scales, "scale factors, their inverses, sigma^2 and its inverse");

  // Frame::ExtractORB: a lapping area puts its keypoints last; the return value counts the others.
  std::vector<cv::KeyPoint> keys;
  cv::Mat descriptors;
  std::vector<int> lapping;
  lapping.push_back(300);
  lapping.push_back(450);
  const int monocular = (*extractor)(image, cv::Mat(), keys, descriptors, lapping);
  check(!keys.empty() && descriptors.rows == static_cast<int>(keys.size()) && descriptors.cols == 32,
        "keypoints and 32-byte descriptors");
  bool ordered = monocular > 0 && monocular < static_cast<int>(keys.size());
  bool sizes = true;
  for (size_t i = 0; i < keys.size(); ++i) {
    const bool inside = keys[i].pt.x >= 300 && keys[i].pt.x <= 450;
    ordered = ordered && inside == (static_cast<int>(i) >= monocular);
    sizes = sizes && keys[i].octave >= 0 && keys[i].octave < levels &&
            std::fabs(keys[i].size - 31.f * factors[keys[i].octave]) < 1e-3f;
  }
  check(ordered, "lapping-area keypoints last, the return value the number before them");
  check(sizes, "octave and size 31 x scale on every keypoint");

  // ORBmatcher::ComputeStereoMatches reads the pyramid after the call.
  bool pyramid = extractor->mvImagePyramid.size() == 8u;
  for (int l = 0; pyramid && l < levels; ++l) {
    const cv::Mat& level = extractor->mvImagePyramid[l];
    pyramid = level.type() == CV_8UC1 && level.cols == cvRound(image.cols / factors[l]) &&
              level.rows == cvRound(image.rows / factors[l]);
  }
  check(pyramid, "mvImagePyramid: one 8-bit image per level, round(size / scale)");

  // ORB-SLAM2's call, and an empty image as ORB-SLAM3 reports it.
  std::vector<cv::KeyPoint> keys2;
  cv::Mat descriptors2;
  (*extractor)(image, cv::Mat(), keys2, descriptors2);
  check(keys2.size() == keys.size(), "the ORB-SLAM2 call finds the same keypoints");
  std::vector<cv::KeyPoint> none;
  check((*extractor)(cv::Mat(), cv::Mat(), none, descriptors, lapping) == -1, "an empty image gives -1");
  delete extractor;
  return installed::verdict("written_for_orb_slam");
}
