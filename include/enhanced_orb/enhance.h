// Section III-A of the paper: gray conversion and image enhancement (Gaussian filter, a
// histogram-driven tone curve, unsharp masking).
#ifndef ENHANCED_ORB_ENHANCE_H
#define ENHANCED_ORB_ENHANCE_H

#include <array>
#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

#include "enhanced_orb/params.h"

namespace enhanced_orb {

// Pixel layouts the library turns into 8-bit gray.
enum class PixelFormat { kMono8, kMono16, kBGR, kRGB, kBGRA, kRGBA };

// Converts an image of the given layout to 8-bit gray: colour with the usual luma weights
// (cv::cvtColor), 16-bit scaled by 1/257. A mono8 input is returned without a copy.
// Throws std::invalid_argument when the Mat's type does not match `format`.
cv::Mat toGray(const cv::Mat& image, PixelFormat format);

// Eq 7: lambda, the standard deviation of the image scaled to [0, 1]. 0 for an empty image. With
// `mean_gray`, also the image's mean, from the same pass.
double imageLambda(const cv::Mat& gray, double* mean_gray = nullptr);

// Step 3: whether the image counts as poor quality, by `gamma_mode` and the test on lambda.
bool isPoorQuality(double lambda, const EnhanceParams& params);

using Histogram = std::array<std::uint32_t, 256>;
using WeightedHistogram = std::array<double, 256>;
// A tone curve as a table: the output tone of each input tone 0..255 (the gamma, equalising and
// stretching curves alike).
using ToneLut = std::array<float, 256>;

// Eqs 10-13: the cumulative weighted distribution C_w of a histogram (counts or weights), with
// the smoothness exponent alpha. All zero for an empty histogram.
std::array<double, 256> weightedCdf(const WeightedHistogram& histogram, double alpha);

// Eqs 10-16: the truncated adaptive gamma table LUT(i) = 255 (i/255)^gamma_i of a histogram.
ToneLut truncatedGammaLut(const Histogram& histogram, double alpha, double tau);

// The default mode's tone curve: LUT(i) = 255 (tau i/255 + (1 - tau) C_w(i)), an equalisation by
// the weighted CDF whose slope never falls below tau. The identity for an empty histogram.
ToneLut equalizingLut(const WeightedHistogram& histogram, double alpha, double tau);

// tone_curve stretch: LUT(i) = 255 (i - lo) / (hi - lo), clamped to [0, 255], where lo is the
// lowest level with more than tau n of the n pixels at or below it and hi the highest with more than
// tau n at or above it: a fraction tau of the pixels is clipped at each end and the tones keep their
// order and their ratios of contrast. The identity when hi <= lo (an empty or one-tone histogram).
ToneLut stretchingLut(const Histogram& histogram, double tau);

// The default mode's histogram of `f` (the filtered image, CV_8UC1): the pixels at even x of even
// rows each add w = sqrt(|f(x+1, y) - f(x-1, y)| + |f(x, y+1) - f(x, y-1)|) (neighbours clamped at
// the border) to the bin of f(x, y), so that flat regions (sky, walls, saturated areas) stop
// driving the curve. Weights are counted in exact 1/64ths (round(64 w)), so any order of summing
// gives the same histogram.
WeightedHistogram edgeWeightedHistogram(const cv::Mat& f);

struct EnhanceResult {
  cv::Mat image;              // enhanced 8-bit gray image, same size as the input
  double lambda = 0.0;        // eq 7, of the input
  double mean_gray = 0.0;     // mean of the input
  bool poor_quality = false;  // step 3: the tone curve was applied
  bool inverted = false;      // step 4 (gamma curve only): worked on the negative of a bright poor image
};

// What enhance() reuses from call to call (fresh buffers of a frame's size would be fresh pages
// from the kernel, whose faults cost more than the arithmetic). One per concurrent caller.
struct EnhanceWorkspace {
  cv::Mat f8;                                          // f, 8 bits (equalize and stretch)
  cv::Mat input_f, f, e, f_rounded, curve_f;           // the gamma curve's float passes
  std::vector<int> starts;                             // the bands' first rows
  std::vector<std::array<std::uint64_t, 256>> counts;  // each band's edge-weighted histogram
};

// The whole enhancement of an 8-bit gray image (ALGORITHM.md section 1). An empty input gives an
// empty result. Throws std::invalid_argument when `gray` is not CV_8UC1 or `params` is invalid.
// `output`, when it has the input's size and type CV_8UC1, receives the result in place (a view of
// a message buffer, say); otherwise a new image is allocated. It may be `gray` itself. With
// params.threads > 1 horizontal bands are worked on side by side (cv::parallel_for_); the result is
// the same for any count. Frame after frame, pass a workspace; without one, each call makes its own.
EnhanceResult enhance(const cv::Mat& gray, const EnhanceParams& params, EnhanceWorkspace& workspace,
                      cv::Mat output = cv::Mat());
EnhanceResult enhance(const cv::Mat& gray, const EnhanceParams& params, cv::Mat output = cv::Mat());

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_ENHANCE_H
