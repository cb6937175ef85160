// Whether the camera of a stream of frames moves, judged from the frames in order: the default
// mode's selection for a still camera keeps each level's strongest corners (they are found again
// when the light changes), for a moving one spreads the budget over the image (relative pose needs
// corners over the whole view); docs/RESULTS.md, "Real camera motion".
//
// Each frame's shift against a reference frame is measured by phase correlation (the normalised
// cross-power spectrum of two small thumbnails; the peak of its inverse is at the shift). It
// whitens both spectra, so a change of exposure, gain or noise level moves no peak: on the EuRoC
// frames of a static camera, darkened, flickering or switched off, the shift stays under 2 pixels,
// while a hand-carried camera at 20 Hz shifts about 10 pixels a frame.
#ifndef ENHANCED_ORB_CAMERA_MOTION_H
#define ENHANCED_ORB_CAMERA_MOTION_H

#include <vector>

#include <opencv2/core.hpp>

namespace enhanced_orb {

class CameraMotion {
public:
  // The camera has moved once a frame is this fraction of the image width away from the reference
  // frame (about 4 pixels at 752: twice the largest shift measured on a still camera in the dark).
  static constexpr double kMovedFraction = 0.005;
  // It is judged moving for this many frames after it last moved (1.5 s at 20 Hz), so a slow
  // camera, whose shift grows over several frames, is judged moving all along.
  static constexpr int kHoldFrames = 30;
  // Thumbnails are the frame halved while the half is at least kThumbnailWidth wide (752 x 480:
  // 94 x 60); a frame whose thumbnail is smaller than kMinThumbnail on a side is not judged (the
  // camera stays judged still).
  static constexpr int kThumbnailWidth = 64;
  static constexpr int kMinThumbnail = 16;

  // Takes the stream's next frame (CV_8UC1, any size; another type or an empty frame is not
  // judged and changes nothing) and returns whether the camera is now judged to move. A frame of
  // another size than the last starts a new stream. The first frame of a stream is judged still.
  bool update(const cv::Mat& gray);

  bool moving() const { return since_moved_ < kHoldFrames; }
  // The last judged frame's shift from the reference frame, in pixels of the frame (0 for the first).
  double shift() const { return shift_; }

  // Forgets the stream: the next frame starts a new one.
  void reset();

private:
  // The windowed thumbnail's spectrum of `gray` into `spectrum`.
  void spectrumOf(const cv::Mat& gray, cv::Mat& spectrum);
  // The shift between the reference's spectrum and `spectrum`, in thumbnail pixels.
  double shiftTo(const cv::Mat& spectrum);

  cv::Size frame_size_, thumbnail_;
  std::vector<cv::Mat> halves_;  // the frame halved once, twice, ... (the last is the thumbnail)
  cv::Mat reference_;            // the reference frame's spectrum (CV_32FC2); empty: no stream yet
  cv::Mat window_;               // Hann window of the thumbnail's size
  cv::Mat thumb_, padded_, spectrum_, cross_, correlation_;  // padded_: the DFT's size, zero outside the thumbnail
  int since_moved_ = kHoldFrames;                            // frames since the camera last moved
  double shift_ = 0.0;
};

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_CAMERA_MOTION_H
