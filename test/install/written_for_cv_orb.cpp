// A program written for cv::ORB; the one line that creates the detector is all that changed.
// Checks what such code relies on: detectAndCompute with a mask, compute on given keypoints,
// the descriptor's size, type and norm, matching with cv::BFMatcher, drawing with cv::drawKeypoints.
//   written_for_cv_orb IMAGE     exit 0 when every check holds, 1 otherwise
#include <vector>

#include <opencv2/features2d.hpp>

#include <enhanced_orb/feature2d.h>

#include "checks.h"

using installed::check;

int main(int argc, char** argv) {
  const cv::Mat image = installed::frameFromArguments(argc, argv, "written_for_cv_orb");
  if (image.empty()) {
    return argc == 2 ? 1 : 2;
  }
  // was: cv::Ptr<cv::Feature2D> orb = cv::ORB::create(1000);
  cv::Ptr<cv::Feature2D> orb = enhanced_orb::ORB::create();

  cv::Mat mask(image.size(), CV_8UC1, cv::Scalar(255));
  mask(cv::Rect(0, 0, image.cols / 2, image.rows)).setTo(0);
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb->detectAndCompute(image, mask, keypoints, descriptors);
  check(keypoints.size() > 100 && static_cast<int>(keypoints.size()) == descriptors.rows,
        "detectAndCompute: keypoints, one descriptor row each");
  bool outside = true;
  for (const cv::KeyPoint& kp : keypoints) {
    outside = outside && mask.at<uchar>(cvRound(kp.pt.y), cvRound(kp.pt.x)) != 0;
  }
  check(outside, "no keypoint where the mask is 0");
  check(orb->descriptorSize() == 32 && orb->descriptorType() == CV_8U && descriptors.cols == 32 &&
            descriptors.type() == CV_8U && orb->defaultNorm() == cv::NORM_HAMMING,
        "32-byte CV_8U descriptors, NORM_HAMMING");

  std::vector<cv::KeyPoint> detected;
  orb->detect(image, detected, mask);
  cv::Mat computed;
  orb->compute(image, detected, computed);
  check(detected.size() == keypoints.size() && cv::norm(computed, descriptors, cv::NORM_INF) == 0.0,
        "detect then compute gives what detectAndCompute gives");

  cv::BFMatcher matcher(orb->defaultNorm(), true);
  std::vector<cv::DMatch> matches;
  matcher.match(descriptors, computed, matches);
  check(matches.size() == keypoints.size(), "cv::BFMatcher matches every descriptor with itself");
  cv::Mat drawn;
  cv::drawKeypoints(image, keypoints, drawn);
  check(drawn.size() == image.size() && drawn.type() == CV_8UC3, "cv::drawKeypoints draws them");
  return installed::verdict("written_for_cv_orb");
}
