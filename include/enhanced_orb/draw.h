// Annotated images that leave the scene visible: keypoints as small marks coloured by octave (at
// most a chosen number, the strongest spread over the image), an octave legend, optional
// orientation ticks, the cell grid with each cell's threshold, and a line of text.
#ifndef ENHANCED_ORB_DRAW_H
#define ENHANCED_ORB_DRAW_H

#include <string>
#include <vector>

#include <opencv2/core.hpp>

namespace enhanced_orb {

struct DrawOptions {
  bool keypoints = true;     // a dot per keypoint, of radius 1 + octave / 2 px
  bool orientation = false;  // a short tick along each keypoint's angle
  bool grid = false;         // the level-0 cell grid, each cell labelled with its FAST threshold
  bool text = true;          // `caption` in the top-left corner and the octave legend
  int max_drawn = 300;       // at most this many keypoints, the strongest spread over the image; 0: all
};

// The colour (BGR) of an octave; the palette repeats after eight octaves.
cv::Scalar octaveColour(int octave);

// Draws onto a BGR copy of `image` (8-bit gray or BGR). `thresholds` may be empty. `canvas`, when
// it has the image's size and type CV_8UC3, receives the drawing in place (a message buffer, say).
cv::Mat drawAnnotated(const cv::Mat& image, const std::vector<cv::KeyPoint>& keypoints, const cv::Mat& thresholds,
                      const std::string& caption, const DrawOptions& options = DrawOptions(),
                      cv::Mat canvas = cv::Mat());

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_DRAW_H
