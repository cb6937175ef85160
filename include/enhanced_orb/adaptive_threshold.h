// Section III-B of the paper: the truncated adaptive FAST threshold of each grid cell.
#ifndef ENHANCED_ORB_ADAPTIVE_THRESHOLD_H
#define ENHANCED_ORB_ADAPTIVE_THRESHOLD_H

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "enhanced_orb/params.h"
#include "enhanced_orb/simd.h"

namespace enhanced_orb {

// Cell (cx, cy) of an m x m grid over an image of `size`: [round(k W/m), round((k+1) W/m)) in x,
// likewise in y. Cells of an image smaller than the grid may be empty.
cv::Rect gridCell(cv::Size size, int grid_size, int cx, int cy);

using CellHistogram = std::array<std::uint32_t, 256>;

// Eqs 21-32: the Otsu threshold t of a histogram (maximal between-class variance, ties to the
// smallest t), in the floating-point steps of cv::threshold's THRESH_OTSU, so that both give the
// same t. 0 for an empty or constant histogram.
int otsuThreshold(const CellHistogram& histogram);
// The same of `count` histograms at once (at most 1024), into thresholds[0..count), by the kernel
// of `level` (or the best one below it that this build has).
void otsuThresholds(const CellHistogram* histograms, int count, int* thresholds, SimdLevel level = activeSimdLevel());

// The same of an 8-bit cell, through cv::threshold: the reference the histogram path is tested against.
int otsuThreshold(const cv::Mat& cell);

// The histograms of every cell of a grid_size x grid_size grid (row-major), in one pass over the image.
std::vector<CellHistogram> cellHistograms(const cv::Mat& image, int grid_size);

// What cellThresholds() needs from call to call, so that repeated calls allocate nothing.
struct ThresholdWorkspace {
  std::vector<CellHistogram> histograms;
  std::vector<std::array<std::uint32_t, 4 * 256>> partial;  // four interleaved counts per cell
};

// cellHistograms() into `ws.histograms`.
void cellHistograms(const cv::Mat& image, int grid_size, ThresholdWorkspace& ws);

// I_mid: the cell's centre pixel, local (rows/2, cols/2).
int centreValue(const cv::Mat& cell);

// Eqs 33-34: max(c_min, lround(threshold_scale |I_mid - t|)), at most 255.
int truncatedThreshold(int i_mid, int otsu, const ThresholdParams& params);

// Eqs 33-34 of one cell (Otsu through cv::threshold); c_min for an empty cell.
int cellThreshold(const cv::Mat& cell, const ThresholdParams& params);

// The grid_size x grid_size (CV_32S, row-major: row = cy) FAST thresholds of an 8-bit image, from
// one histogram pass (cellHistograms); equal to cellThreshold() of every cell.
cv::Mat cellThresholds(const cv::Mat& image, const ThresholdParams& params);
void cellThresholds(const cv::Mat& image, const ThresholdParams& params, ThresholdWorkspace& ws, cv::Mat& thresholds);

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_ADAPTIVE_THRESHOLD_H
