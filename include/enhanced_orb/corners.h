// FAST-9 corners cell by cell, each cell with its own threshold (the adaptive threshold's grid).
#ifndef ENHANCED_ORB_CORNERS_H
#define ENHANCED_ORB_CORNERS_H

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace enhanced_orb {

// Keypoints closer than this to a level's border are not detected: the orientation patch
// (radius 15) and the rotated descriptor pattern (radius < 19) then stay inside the image.
constexpr int kEdgeThreshold = 19;

// What detectCorners() needs from call to call.
struct CornerWorkspace {
  cv::Mat scores;                                     // FAST score of every interior pixel
  std::vector<std::uint8_t> floors;                   // a row's cell thresholds, pixel by pixel
  std::vector<std::uint8_t> rows;                     // the suppression's row buffers
  std::vector<std::vector<cv::KeyPoint>> cell_lists;  // one grid row's corners, cell by cell
};

// FAST-9 with non-maximum suppression, cell by cell with each cell's threshold from `thresholds`
// (grid x grid, CV_32S): the corners cv::FAST finds in each cell's window (the cell widened by 3
// pixels, so that its circle reads the neighbouring pixels), bit for bit, found from one map of
// FAST scores of the level instead, whose cost does not depend on the thresholds. Only corners at
// least kEdgeThreshold from the border are returned, in level coordinates, response = cv::FAST's
// score, cell by cell (row-major), each cell row by row.
void detectCorners(const cv::Mat& level, const cv::Mat& thresholds, CornerWorkspace& ws,
                   std::vector<cv::KeyPoint>& corners);
std::vector<cv::KeyPoint> detectCorners(const cv::Mat& level, const cv::Mat& thresholds);

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_CORNERS_H
