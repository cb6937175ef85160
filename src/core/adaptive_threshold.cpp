#include "enhanced_orb/adaptive_threshold.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>

#include <opencv2/imgproc.hpp>

#include "kernels/dispatch.h"
#include "kernels/otsu.h"

namespace enhanced_orb {

cv::Rect gridCell(cv::Size size, int grid_size, int cx, int cy) {
  auto edge = [grid_size](int length, int k) {
    return static_cast<int>(std::lround(static_cast<double>(k) * length / grid_size));
  };
  const int x0 = edge(size.width, cx);
  const int y0 = edge(size.height, cy);
  return cv::Rect(x0, y0, edge(size.width, cx + 1) - x0, edge(size.height, cy + 1) - y0);
}

namespace {

// The reference (and the kernel where no wider one is built): the cells side by side, level by
// level, each cell's arithmetic that of a single cell, so that their divisions, which wait on one
// another within a cell, overlap.
void otsuThresholdsScalar(const std::uint32_t* histograms, int count, int* thresholds) {
  struct State {
    double scale, mu, q1, mu1, max_sigma;
    int best;
    bool empty;
  };
  State states[1024];
  for (int c = 0; c < count; ++c) {
    State& st = states[c];
    double n = 0.0;
    double mu = 0.0;  // eq 23: the mean level mu_T of the whole cell
    for (int i = 0; i < 256; ++i) {
      n += histograms[256 * c + i];
      mu += i * static_cast<double>(histograms[256 * c + i]);
    }
    st.empty = n == 0.0;
    st.scale = st.empty ? 0.0 : 1.0 / n;
    st.mu = mu * st.scale;
    st.q1 = 0.0;
    st.mu1 = 0.0;
    st.max_sigma = 0.0;
    st.best = 0;
  }
  // Eqs 24-32, one level at a time: omega_0 (q1) and mu_0 (mu1) of the class below t, mu_1 (mu2)
  // of the class above, and the between-class variance omega_0 omega_1 (mu_0 - mu_1)^2, in the
  // floating-point steps of cv::threshold's THRESH_OTSU.
  for (int i = 0; i < 256; ++i) {
    for (int c = 0; c < count; ++c) {
      State& st = states[c];
      const double p_i = histograms[256 * c + i] * st.scale;  // eq 21
      st.mu1 *= st.q1;
      st.q1 += p_i;
      const double q2 = 1.0 - st.q1;
      if (std::min(st.q1, q2) < FLT_EPSILON || std::max(st.q1, q2) > 1.0 - FLT_EPSILON) {
        continue;
      }
      st.mu1 = (st.mu1 + i * p_i) / st.q1;
      const double mu2 = (st.mu - st.q1 * st.mu1) / q2;
      const double sigma = st.q1 * q2 * (st.mu1 - mu2) * (st.mu1 - mu2);
      if (sigma > st.max_sigma) {  // ties keep the smallest t
        st.max_sigma = sigma;
        st.best = i;
      }
    }
  }
  for (int c = 0; c < count; ++c) {
    thresholds[c] = states[c].empty ? 0 : states[c].best;
  }
}

}  // namespace

void otsuThresholds(const CellHistogram* histograms, int count, int* thresholds, SimdLevel level) {
  static_assert(sizeof(CellHistogram) == 256 * sizeof(std::uint32_t), "histograms lie end to end");
  CV_Assert(count >= 0 && count <= 1024);
  if (count == 0) {
    return;
  }
  const kernels::OtsuKernel kernel = kernels::selectKernel<kernels::OtsuKernel>(
      level, otsuThresholdsScalar, nullptr, ENHANCED_ORB_X86_KERNEL(kernels::otsuThresholdsAvx2));
  kernel(histograms[0].data(), count, thresholds);
}

int otsuThreshold(const CellHistogram& histogram) {
  int t = 0;
  otsuThresholds(&histogram, 1, &t);
  return t;
}

void cellHistograms(const cv::Mat& image, int grid_size, ThresholdWorkspace& ws) {
  CV_Assert(image.type() == CV_8UC1 && grid_size >= 1 && grid_size <= 32);
  const size_t cells = static_cast<size_t>(grid_size) * grid_size;
  // Cell edges as gridCell() draws them.
  int x_edges[33], y_edges[33];
  for (int k = 0; k < grid_size; ++k) {
    x_edges[k] = gridCell(image.size(), grid_size, k, 0).x;
    y_edges[k] = gridCell(image.size(), grid_size, 0, k).y;
  }
  x_edges[grid_size] = image.cols;
  y_edges[grid_size] = image.rows;
  // Four partial counts per cell, so that runs of equal pixels do not wait on one counter.
  ws.partial.resize(cells);
  for (auto& counts : ws.partial) {
    counts.fill(0);
  }
  for (int cy = 0; cy < grid_size; ++cy) {
    for (int y = y_edges[cy]; y < y_edges[cy + 1]; ++y) {
      const std::uint8_t* row = image.ptr<std::uint8_t>(y);
      for (int cx = 0; cx < grid_size; ++cx) {
        std::uint32_t* h = ws.partial[static_cast<size_t>(cy) * grid_size + cx].data();
        int x = x_edges[cx];
        for (; x + 4 <= x_edges[cx + 1]; x += 4) {
          ++h[row[x]];
          ++h[256 + row[x + 1]];
          ++h[512 + row[x + 2]];
          ++h[768 + row[x + 3]];
        }
        for (; x < x_edges[cx + 1]; ++x) {
          ++h[row[x]];
        }
      }
    }
  }
  ws.histograms.resize(cells);
  for (size_t c = 0; c < cells; ++c) {
    const std::uint32_t* h = ws.partial[c].data();
    for (int i = 0; i < 256; ++i) {
      ws.histograms[c][i] = h[i] + h[256 + i] + h[512 + i] + h[768 + i];
    }
  }
}

std::vector<CellHistogram> cellHistograms(const cv::Mat& image, int grid_size) {
  ThresholdWorkspace ws;
  cellHistograms(image, grid_size, ws);
  return ws.histograms;
}

int otsuThreshold(const cv::Mat& cell) {
  if (cell.empty()) {
    return 0;
  }
  cv::Mat binary;  // required by the API, not used
  return static_cast<int>(cv::threshold(cell, binary, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU));
}

int centreValue(const cv::Mat& cell) {
  return cell.at<std::uint8_t>(cell.rows / 2, cell.cols / 2);
}

int truncatedThreshold(int i_mid, int otsu, const ThresholdParams& params) {
  const double c = params.threshold_scale * std::abs(i_mid - otsu);  // eq 33
  // Eq 34, capped at 255: no 8-bit pixel differs from another by more, and cv::FAST reads larger
  // thresholds modulo 256 in its vector path.
  return std::min(255, std::max(params.c_min, static_cast<int>(std::lround(c))));
}

int cellThreshold(const cv::Mat& cell, const ThresholdParams& params) {
  if (cell.empty()) {
    return params.c_min;
  }
  return truncatedThreshold(centreValue(cell), otsuThreshold(cell), params);
}

void cellThresholds(const cv::Mat& image, const ThresholdParams& params, ThresholdWorkspace& ws, cv::Mat& thresholds) {
  const int grid = params.grid_size;
  thresholds.create(grid, grid, CV_32S);
  if (params.threshold_scale == 0.0) {
    // Eq 33 gives 0 in every cell and eq 34 c_min: no histogram or Otsu threshold is needed.
    thresholds.setTo(cv::Scalar(std::min(255, params.c_min)));
    return;
  }
  cellHistograms(image, grid, ws);
  int otsu[1024];
  otsuThresholds(ws.histograms.data(), grid * grid, otsu);
  for (int cy = 0; cy < grid; ++cy) {
    for (int cx = 0; cx < grid; ++cx) {
      const cv::Rect rect = gridCell(image.size(), grid, cx, cy);
      int& t = thresholds.at<int>(cy, cx);
      if (rect.empty()) {
        t = params.c_min;
        continue;
      }
      const int i_mid = image.at<std::uint8_t>(rect.y + rect.height / 2, rect.x + rect.width / 2);  // centreValue
      t = truncatedThreshold(i_mid, otsu[cy * grid + cx], params);
    }
  }
}

cv::Mat cellThresholds(const cv::Mat& image, const ThresholdParams& params) {
  ThresholdWorkspace ws;
  cv::Mat thresholds;
  cellThresholds(image, params, ws, thresholds);
  return thresholds;
}

}  // namespace enhanced_orb
