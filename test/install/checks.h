// What the two programs written by users share: a line per check, and the frame they run on.
// C++11, as the ORB-SLAM program builds.
#ifndef ENHANCED_ORB_INSTALL_CHECKS_H
#define ENHANCED_ORB_INSTALL_CHECKS_H

#include <iostream>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

namespace installed {

inline int& failures() {
  static int count = 0;
  return count;
}

// Prints "ok" or "FAILED" and the check; counts the failures.
inline void check(bool ok, const char* what) {
  std::cout << (ok ? "ok     " : "FAILED ") << what << "\n";
  failures() += ok ? 0 : 1;
}

// The gray frame named by the program's one argument; empty (with a message) when there is none.
inline cv::Mat frameFromArguments(int argc, char** argv, const char* program) {
  if (argc != 2) {
    std::cerr << "usage: " << program << " IMAGE\n";
    return cv::Mat();
  }
  const cv::Mat image = cv::imread(argv[1], cv::IMREAD_GRAYSCALE);
  if (image.empty()) {
    std::cerr << program << ": cannot read " << argv[1] << "\n";
  }
  return image;
}

// The program's exit code: 0 when every check held, 1 otherwise.
inline int verdict(const char* program) {
  std::cout << program << (failures() ? ": FAILED\n" : ": passed\n");
  return failures() ? 1 : 0;
}

}  // namespace installed

#endif
