// The noise of a frame, measured on the image the corners are detected on.
#ifndef ENHANCED_ORB_NOISE_H
#define ENHANCED_ORB_NOISE_H

#include <opencv2/core.hpp>

namespace enhanced_orb {

// The standard deviation of the pixel noise of an 8-bit gray image, in gray levels: Immerkær's
// Laplacian-difference operator (Immerkær, "Fast noise variance estimation", CVIU 64(2), 1996),
// N = [1 -2 1; -2 4 -2; 1 -2 1], here on pixels two apart (so that the noise of a filtered image,
// correlated between neighbours, still counts), whose response to white noise of deviation s has
// deviation 6 s, taken robustly as the median absolute response / 0.6745 so that edges and texture
// (the few large responses) do not count. Read on every `row_step`-th row from the third. 0 for an
// image smaller than 5 x 5.
double estimateNoise(const cv::Mat& gray, int row_step = 4);

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_NOISE_H
