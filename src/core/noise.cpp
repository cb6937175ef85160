#include "enhanced_orb/noise.h"

#include <array>
#include <cstdint>
#include <cstdlib>

namespace enhanced_orb {

double estimateNoise(const cv::Mat& gray, int row_step) {
  CV_Assert(gray.empty() || gray.type() == CV_8UC1);
  if (gray.rows < 5 || gray.cols < 5) {
    return 0.0;
  }
  // |N * I| ranges over [0, 16 * 255]: a histogram gives the median without sorting.
  std::array<std::uint32_t, 16 * 255 + 1> histogram{};
  std::uint64_t count = 0;
  for (int y = 2; y + 2 < gray.rows; y += std::max(1, row_step)) {
    const std::uint8_t* a = gray.ptr<std::uint8_t>(y - 2);
    const std::uint8_t* b = gray.ptr<std::uint8_t>(y);
    const std::uint8_t* c = gray.ptr<std::uint8_t>(y + 2);
    for (int x = 2; x + 2 < gray.cols; ++x) {
      const int r =
          a[x - 2] - 2 * a[x] + a[x + 2] - 2 * (b[x - 2] - 2 * b[x] + b[x + 2]) + c[x - 2] - 2 * c[x] + c[x + 2];
      ++histogram[std::abs(r)];
    }
    count += static_cast<std::uint64_t>(gray.cols - 4);
  }
  std::uint64_t seen = 0;
  int median = 0;
  while (median < static_cast<int>(histogram.size()) - 1 && (seen += histogram[median]) * 2 < count) {
    ++median;
  }
  return median / (0.6745 * 6.0);
}

}  // namespace enhanced_orb
