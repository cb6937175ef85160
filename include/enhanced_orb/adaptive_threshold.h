// Section III-B of the paper: the truncated adaptive FAST threshold of each grid cell.
#ifndef ENHANCED_ORB_ADAPTIVE_THRESHOLD_H
#define ENHANCED_ORB_ADAPTIVE_THRESHOLD_H

#include <opencv2/core.hpp>

#include "enhanced_orb/params.h"

namespace enhanced_orb {

// Cell (cx, cy) of an m x m grid over an image of `size`: [round(k W/m), round((k+1) W/m)) in x,
// likewise in y. Cells of an image smaller than the grid may be empty.
cv::Rect gridCell(cv::Size size, int grid_size, int cx, int cy);

// Eqs 21-32: the Otsu threshold t of an 8-bit cell (maximal between-class variance, ties to the
// smallest t), as cv::threshold's THRESH_OTSU computes it. 0 for an empty or constant cell.
int otsuThreshold(const cv::Mat& cell);

// I_mid: the cell's centre pixel, local (rows/2, cols/2).
int centreValue(const cv::Mat& cell);

// Eqs 33-34: max(c_min, lround(threshold_scale |I_mid - t|)) of one cell; c_min for an empty cell.
int cellThreshold(const cv::Mat& cell, const ThresholdParams& params);

// The grid_size x grid_size (CV_32S, row-major: row = cy) FAST thresholds of an 8-bit image.
cv::Mat cellThresholds(const cv::Mat& image, const ThresholdParams& params);

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_ADAPTIVE_THRESHOLD_H
