// ORB with the truncated adaptive threshold: pyramid, per-cell FAST, orientation by intensity
// centroid, rBRIEF descriptors interchangeable with cv::ORB's, and the two keypoint budgets.
#ifndef ENHANCED_ORB_ORB_EXTRACTOR_H
#define ENHANCED_ORB_ORB_EXTRACTOR_H

#include <cstdint>
#include <memory>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/features2d.hpp>

#include "enhanced_orb/params.h"

namespace enhanced_orb {

// Keypoints closer than this to a level's border are not detected: the orientation patch
// (radius 15) and the rotated descriptor pattern (radius < 19) then stay inside the image.
constexpr int kEdgeThreshold = 19;
// ORB's patch diameter; a keypoint of octave o has size kPatchSize * scale_factor^o.
constexpr int kPatchSize = 31;
// Descriptor length in bytes (256 bits).
constexpr int kDescriptorBytes = 32;

// Time of each stage of one extraction, in milliseconds. With threads > 1 the levels' stages run
// side by side: each stage is then its time summed over the levels, and extract_ms (wall clock)
// is less than their sum.
struct StageTimings {
  double enhance_ms = 0.0;
  double pyramid_ms = 0.0;
  double threshold_ms = 0.0;
  double fast_ms = 0.0;
  double select_ms = 0.0;
  double orientation_ms = 0.0;
  double descriptor_ms = 0.0;  // smoothing and rBRIEF
  double extract_ms = 0.0;     // wall clock of everything after the enhancement

  double extractMs() const { return extract_ms; }
  double totalMs() const { return enhance_ms + extract_ms; }
};

struct Extraction {
  std::vector<cv::KeyPoint> keypoints;    // level-0 coordinates; size, angle (degrees), response, octave
  cv::Mat descriptors;                    // keypoints.size() x kDescriptorBytes, CV_8U
  cv::Mat cell_thresholds;                // grid_size x grid_size CV_32S, level 0
  std::vector<cv::Mat> level_thresholds;  // the same for every pyramid level
  cv::Mat image;                          // the 8-bit image features were extracted from (enhanced or input)
  double lambda = 0.0;                    // eq 7 of the input (0 when enhancement is off)
  bool poor_quality = false;
  bool inverted = false;
  double noise = 0.0;  // estimateNoise() of `image` where noise_floor uses it, else 0
  StageTimings timings;
};

// Section II-C: level 0 is `image`, level i is level i-1 resized (INTER_LINEAR_EXACT, as cv::ORB)
// to round(size / scale_factor^i). Stops early when a level would have no pixel.
std::vector<cv::Mat> buildPyramid(const cv::Mat& image, int n_levels, double scale_factor);

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

// How a budget of `total` keypoints splits over the levels: geometric with ratio 1/scale_factor
// (as ORB-SLAM); the last level takes the rounding remainder.
std::vector<int> levelBudgets(int total, int n_levels, double scale_factor);

// Keeps the `n` strongest keypoints (by response; ties by position, y then x), in their order.
void keepStrongest(std::vector<cv::KeyPoint>& keypoints, size_t n);

// Keeps at most `n` keypoints, spread over the image: keypoints are bucketed in square cells of
// about sqrt(area / n) pixels, and taken best response first from every cell in turn: round r
// takes each cell's r-th best, cell by cell; the last, partial round its best responses, best
// first. Fewer than `n` keypoints are returned as they are.
std::vector<cv::KeyPoint> selectSpread(std::vector<cv::KeyPoint> keypoints, int n, cv::Size size);

// Eqs 4-6: the angle (degrees, [0, 360)) of each keypoint by the intensity centroid of the
// circular patch of radius 15 around it. Keypoints whose patch leaves the image get angle 0.
void computeOrientation(const cv::Mat& level, std::vector<cv::KeyPoint>& keypoints);

class OrbExtractor {
public:
  // Throws std::invalid_argument, with every offending parameter named, when `params` is invalid.
  explicit OrbExtractor(const Params& params = Params());

  const Params& params() const { return params_; }

  // Extracts from an 8-bit gray image. An empty image gives an empty result.
  // Throws std::invalid_argument when `gray` is not CV_8UC1.
  Extraction extract(const cv::Mat& gray) const;

  // The same into `out`, reusing its buffers: in a loop over frames of one size nothing is
  // allocated once the first frame is done. Headers kept from an earlier result share those
  // buffers and see them overwritten.
  //
  // An extractor keeps a workspace (pyramid, score maps, histograms, keypoint lists) per
  // concurrent call and reuses it: calls from several threads at once are safe and get the
  // results of sequential calls; copies of an extractor share its workspaces.
  void extract(const cv::Mat& gray, Extraction& out) const;

  struct Workspace;

private:
  std::unique_ptr<Workspace> acquire() const;
  void release(std::unique_ptr<Workspace> ws) const;

  Params params_;
  struct Pool;
  std::shared_ptr<Pool> pool_;
};

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_ORB_EXTRACTOR_H
