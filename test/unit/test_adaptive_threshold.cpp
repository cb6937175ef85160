#include <algorithm>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/adaptive_threshold.h"
#include "enhanced_orb/orb_extractor.h"
#include "test_images.h"

using namespace enhanced_orb;

namespace {

// Eqs 21-32 by brute force: the t maximising the between-class variance w0 w1 (mu0 - mu1)^2 of
// the classes {<= t} and {> t}, smallest t on ties; 0 when no t splits the cell.
int bruteForceOtsu(const cv::Mat& cell) {
  std::vector<double> hist(256, 0.0);
  for (int y = 0; y < cell.rows; ++y) {
    for (int x = 0; x < cell.cols; ++x) {
      hist[cell.at<uchar>(y, x)] += 1.0;
    }
  }
  const double n = cell.total();
  double best = -1.0;
  int best_t = 0;
  for (int t = 0; t < 256; ++t) {
    double n0 = 0.0, s0 = 0.0, s1 = 0.0;
    for (int i = 0; i < 256; ++i) {
      (i <= t ? s0 : s1) += i * hist[i];
      n0 += i <= t ? hist[i] : 0.0;
    }
    const double n1 = n - n0;
    if (n0 == 0.0 || n1 == 0.0) {
      continue;
    }
    const double diff = s0 / n0 - s1 / n1;
    const double between = (n0 / n) * (n1 / n) * diff * diff;
    if (between > best * (1.0 + 1e-12)) {
      best = between;
      best_t = t;
    }
  }
  return best_t;
}

}  // namespace

TEST(GridCell, CellsTileTheImageWithRoundedEdges) {
  // 752 / 5 = 150.4: edges at 0, 150, 301, 451, 602, 752.
  const std::vector<int> edges = {0, 150, 301, 451, 602, 752};
  for (int k = 0; k < 5; ++k) {
    const cv::Rect cell = gridCell(cv::Size(752, 480), 5, k, 0);
    EXPECT_EQ(cell.x, edges[k]);
    EXPECT_EQ(cell.x + cell.width, edges[k + 1]);
    EXPECT_EQ(cell.height, 96);
  }
  for (const cv::Size size : {cv::Size(641, 479), cv::Size(3, 2), cv::Size(1, 1)}) {
    for (int grid : {1, 3, 5, 7}) {
      cv::Mat cover(size, CV_32S, cv::Scalar(0));
      for (int cy = 0; cy < grid; ++cy) {
        for (int cx = 0; cx < grid; ++cx) {
          cv::Mat cell = cover(gridCell(size, grid, cx, cy));
          if (!cell.empty()) {
            cell += 1;
          }
        }
      }
      EXPECT_EQ(cv::countNonZero(cover != 1), 0) << size << " grid " << grid;
    }
  }
}

TEST(Otsu, EqualsTheBetweenClassVarianceDefinition) {
  cv::RNG rng(42);
  for (int trial = 0; trial < 200; ++trial) {
    cv::Mat cell(rng.uniform(4, 80), rng.uniform(4, 80), CV_8UC1);
    // Two noisy modes, or plain uniform noise, so that thresholds fall everywhere.
    const int a = rng.uniform(0, 256), b = rng.uniform(0, 256), spread = rng.uniform(1, 60);
    for (auto it = cell.begin<uchar>(); it != cell.end<uchar>(); ++it) {
      const int centre = trial % 3 == 0 ? rng.uniform(0, 256) : (rng.uniform(0, 2) ? a : b);
      *it = cv::saturate_cast<uchar>(centre + rng.gaussian(spread));
    }
    EXPECT_EQ(otsuThreshold(cell), bruteForceOtsu(cell)) << "trial " << trial;
  }
}

TEST(Otsu, ConstantAndEmptyCells) {
  EXPECT_EQ(otsuThreshold(cv::Mat(5, 5, CV_8UC1, cv::Scalar(90))), 0);
  EXPECT_EQ(otsuThreshold(cv::Mat()), 0);
}

TEST(CentreValue, IsTheLocalCentrePixelInIntegerDivision) {
  cv::Mat cell(4, 5, CV_8UC1, cv::Scalar(0));
  cell.at<uchar>(2, 2) = 99;  // rows / 2 = 2, cols / 2 = 2
  EXPECT_EQ(centreValue(cell), 99);
  cv::Mat big(10, 10, CV_8UC1, cv::Scalar(1));
  big.at<uchar>(5, 5) = 33;
  EXPECT_EQ(centreValue(big(cv::Rect(2, 2, 6, 6))), 33);  // a ROI: local coordinates (3, 3)
}

TEST(CellThreshold, EquationsThirtyThreeAndThirtyFour) {
  // Left half 50, right half 200: Otsu t = 50 (the smallest best split).
  cv::Mat cell(10, 10, CV_8UC1, cv::Scalar(50));
  cell.colRange(5, 10).setTo(200);
  ASSERT_EQ(otsuThreshold(cell), 50);
  ThresholdParams p;
  p.threshold_scale = 0.3;                // the paper's a
  EXPECT_EQ(cellThreshold(cell, p), 45);  // I_mid = 200: 0.3 * 150
  p.c_min = 50;
  EXPECT_EQ(cellThreshold(cell, p), 50);  // truncated at c_min
  p.c_min = 7;
  p.threshold_scale = 0.1;
  EXPECT_EQ(cellThreshold(cell, p), 15);
  cell.at<uchar>(5, 5) = 50;  // I_mid = t: C = 0, so c_min
  EXPECT_EQ(cellThreshold(cell, p), 7);
  EXPECT_EQ(cellThreshold(cv::Mat(), p), 7);  // an empty cell gets c_min
}

TEST(CellThresholds, GridShapeAndLowerBound) {
  const cv::Mat image = test::syntheticScene();
  ThresholdParams p;
  for (int grid : {1, 5, 8}) {
    p.grid_size = grid;
    const cv::Mat t = cellThresholds(image, p);
    ASSERT_EQ(t.type(), CV_32S);
    ASSERT_EQ(t.size(), cv::Size(grid, grid));
    double lo = 0.0;
    cv::minMaxLoc(t, &lo);
    EXPECT_GE(lo, p.c_min);
    for (int cy = 0; cy < grid; ++cy) {
      for (int cx = 0; cx < grid; ++cx) {
        EXPECT_EQ(t.at<int>(cy, cx), cellThreshold(image(gridCell(image.size(), grid, cx, cy)), p));
      }
    }
  }
}

TEST(AdaptiveThreshold, HistogramOtsuEqualsCvThresholdOnEveryCellOfEveryLevel) {
  std::vector<cv::Mat> images;
  const cv::Mat frame = test::eurocFrame();
  images.push_back(frame.empty() ? test::syntheticScene(cv::Size(752, 480), 300) : frame);
  cv::Mat dark, noisy;
  images[0].convertTo(dark, CV_8U, 0.2);
  images.push_back(dark);
  cv::RNG rng(5);
  noisy = images[0].clone();
  rng.fill(noisy, cv::RNG::UNIFORM, 0, 256);
  images.push_back(noisy);
  images.push_back(cv::Mat(37, 23, CV_8UC1, cv::Scalar(9)));  // constant, cells of uneven size
  int cells = 0;
  for (const cv::Mat& image : images) {
    for (const cv::Mat& level : buildPyramid(image, 8, 1.2)) {
      for (int grid : {1, 5, 7}) {
        const std::vector<CellHistogram> h = cellHistograms(level, grid);
        for (int cy = 0; cy < grid; ++cy) {
          for (int cx = 0; cx < grid; ++cx) {
            const cv::Mat cell = level(gridCell(level.size(), grid, cx, cy));
            ASSERT_EQ(otsuThreshold(h[static_cast<size_t>(cy) * grid + cx]), otsuThreshold(cell))
                << "level " << level.size() << " grid " << grid << " cell " << cx << "," << cy;
            ++cells;
          }
        }
      }
    }
  }
  EXPECT_GT(cells, 1000);
}

TEST(Otsu, ManyCellsAtOnceEqualEachCellThroughCvThreshold) {
  // Cells of every kind worked on side by side: narrow and wide level ranges, at either end of
  // [0, 255], two values, constant, empty; from one cell to the most otsuThresholds takes; by the
  // kernel of every instruction set.
  cv::RNG rng(17);
  for (int count : {1, 2, 3, 5, 25, 32, 33, 64, 200, 1024}) {
    std::vector<cv::Mat> cells;
    std::vector<CellHistogram> histograms;
    for (int c = 0; c < count; ++c) {
      const int kind = rng.uniform(0, 6);
      cv::Mat cell(rng.uniform(1, 40), rng.uniform(1, 40), CV_8UC1);
      const int low = kind == 1 ? 0 : kind == 2 ? rng.uniform(200, 256) : rng.uniform(0, 200);
      const int high = kind == 4 ? low : std::min(255, low + (kind == 0 ? 255 : rng.uniform(0, 40)));
      for (auto it = cell.begin<uchar>(); it != cell.end<uchar>(); ++it) {
        *it = static_cast<uchar>(kind == 3 ? (rng.uniform(0, 2) ? low : high) : rng.uniform(low, high + 1));
      }
      if (kind == 5 && rng.uniform(0, 2)) {
        cell = cv::Mat();
      }
      cells.push_back(cell);
      histograms.push_back(cell.empty() ? CellHistogram{} : cellHistograms(cell, 1).front());
    }
    for (SimdLevel level : supportedSimdLevels()) {
      std::vector<int> thresholds(static_cast<size_t>(count) + 1, -1);
      otsuThresholds(histograms.data(), count, thresholds.data(), level);
      for (int c = 0; c < count; ++c) {
        ASSERT_EQ(thresholds[c], otsuThreshold(cells[c])) << toString(level) << ", cell " << c << " of " << count;
      }
      ASSERT_EQ(thresholds[count], -1) << toString(level) << ": written past " << count << " cells";
    }
  }
}
