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
//
// The same correlation tells a new scene from a moving camera: two views of one scene, moved or
// not, correlate in one sharp peak, two unrelated images do not. A frame whose peak is both weak
// against the correlation's spread and hardly above the next highest value is a new scene (a jump
// in a folder of images, a camera switch): the shift is measured from it anew instead of counting
// as motion, and the judgment stays as it was (still for a folder of still scenes; a moving camera
// whose frame went black for a moment stays moving).
#ifndef ENHANCED_ORB_CAMERA_MOTION_H
#define ENHANCED_ORB_CAMERA_MOTION_H

#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/core/hal/hal.hpp>

namespace enhanced_orb {

// What a stream's frames say about its latest one (CameraMotion::judge()).
struct StreamJudgment {
  bool moving = false;          // CameraMotion::update()
  double stream_lambda = -1.0;  // CameraMotion::streamLambda()
};

class CameraMotion {
public:
  // How a stream's first frame is judged, before a second frame can say whether the camera moves.
  enum class Start {
    kStill,   // still: a folder of images, a camera whose motion is not known
    kMoving,  // moving, for that frame only: a SLAM front end's camera, which must move to start a
              // map and whose first frames start it (ORB-SLAM's monocular map is made from two of
              // them, and frames of one selection match each other best). A frame too small to
              // judge keeps this start.
  };

  explicit CameraMotion(Start start = Start::kStill) : start_(start) { reset(); }

  // The camera has moved once a frame is this fraction of the image width away from the last moved
  // frame (about 4 pixels at 752: twice the largest shift measured on a still camera in the dark),
  // and at least kMinMovedShift pixels of the thumbnail (below it the shift is within the error
  // of a peak's centroid: a tripod's exposure bracket, dark to bright, shows up to 0.35).
  static constexpr double kMovedFraction = 0.005;
  static constexpr double kMinMovedShift = 0.4;
  // It is judged moving for this many frames after it last moved (1.5 s at 20 Hz), so a slow
  // camera, whose shift grows over several frames, is judged moving all along.
  static constexpr int kHoldFrames = 30;
  // Thumbnails are the frame halved while the half is at least kThumbnailWidth wide (752 x 480:
  // 94 x 60); a frame whose thumbnail is smaller than kMinThumbnail on a side is not judged (the
  // camera stays judged still).
  static constexpr int kThumbnailWidth = 64;
  static constexpr int kMinThumbnail = 16;
  // A frame is a new scene when its correlation with the last frame peaks below kNewSceneStrength
  // standard deviations of the correlation and below kNewScenePeakRatio times the correlation's
  // highest value outside the peak's 5 x 5. Measured here on thumbnails of consecutive images:
  // unrelated ones (the lighting sets' changes of scene, EuRoC against EuRoC) at most 8.4 and 1.34;
  // a camera's consecutive frames (EuRoC still and moving, KITTI driving, under every light
  // condition of the sequence evaluation) below both in 5 of 6400, all in the dark.
  static constexpr double kNewSceneStrength = 10.0;
  static constexpr double kNewScenePeakRatio = 1.5;
  // A shift from the reference is trusted when the peak is at least this many times the next
  // highest value (else two places match about as well: the exposure bracket's darkest image
  // against its brightest).
  static constexpr double kUnambiguousPeakRatio = 1.2;

  // A moving camera's frames are matched with each other, so they are enhanced alike: the tone
  // curve's quality test (section III-A, step 3) reads the least lambda of the stream's last
  // kToneFrames frames (streamLambda()), not each frame's own. A frame whose lambda alone would
  // pass the test, between others that do not (a contrasty outdoor scene near the threshold,
  // flickering light), then gets no curve like them; a stream that stays poor gets it on every
  // frame (docs/RESULTS.md, "A moving camera's tone curve").
  static constexpr int kToneFrames = 5;

  // Takes the stream's next frame (CV_8UC1, any size; another type or an empty frame is not
  // judged and changes nothing) and returns whether the camera is now judged to move. A frame of
  // another size than the last starts a new stream. The first frame of a stream is judged as
  // Start says; a new scene keeps the judgment as it was.
  bool update(const cv::Mat& gray);

  // update(gray), with streamLambda() after it.
  StreamJudgment judge(const cv::Mat& gray) {
    const bool judged_moving = update(gray);
    return {judged_moving, streamLambda()};
  }

  bool moving() const { return since_moved_ < kHoldFrames; }
  // The last judged frame's shift from the last moved frame, in pixels of the frame (0 for the first
  // frame of a stream and for a new scene).
  double shift() const { return shift_; }
  // Whether the last judged frame was a new scene (unrelated to the frame before it), where the
  // shift is measured from anew.
  bool newScene() const { return new_scene_; }

  // The least lambda (eq 7, enhance.h imageLambda()) of the stream's last kToneFrames frames, this
  // one's included, since the stream or its scene began; -1 before a frame.
  double streamLambda() const;

  // Forgets the stream: the next frame starts a new one.
  void reset();

  Start start() const { return start_; }

private:
  // The windowed thumbnail's spectrum of `gray` into `spectrum`.
  void spectrumOf(const cv::Mat& gray, cv::Mat& spectrum);
  // The phase correlation of two frames' spectra.
  struct Correlation {
    cv::Point2d shift;        // of the second frame from the first, in thumbnail pixels
    double strength = 0.0;    // the peak in standard deviations of the correlation
    double peak_ratio = 0.0;  // the peak over the highest value outside its 5 x 5
    // Views of one scene: one of the two measures clears its bound.
    bool related() const { return strength >= kNewSceneStrength || peak_ratio >= kNewScenePeakRatio; }
    // A peak to measure a shift by: clearly above any other.
    bool unambiguous() const { return related() && peak_ratio >= kUnambiguousPeakRatio; }
  };
  Correlation correlate(const cv::Mat& first, const cv::Mat& second);

  // The planned forward and inverse DFTs of the thumbnail's padded size. A copy of a CameraMotion
  // plans its own (a plan keeps working buffers: two streams must not share one).
  struct Plans {
    cv::Ptr<cv::hal::DFT2D> forward, inverse;
    Plans() = default;
    Plans(const Plans&) {}
    Plans& operator=(const Plans&) {
      forward.reset();
      inverse.reset();
      return *this;
    }
  };

  Start start_ = Start::kStill;
  cv::Size frame_size_, thumbnail_;
  Plans plans_;
  std::vector<cv::Mat> halves_;  // the frame halved once, twice, ... (the last is the thumbnail)
  cv::Mat reference_;            // the reference frame's spectrum (CV_32FC2); empty: no stream yet
  cv::Mat previous_;             // the last frame's spectrum
  bool reference_is_previous_ = false;
  cv::Point2d reference_shift_;  // the reference's shift from the last moved frame, in thumbnail pixels
  cv::Mat window_;               // Hann window of the thumbnail's size
  cv::Mat thumb_, padded_, spectrum_, cross_, correlation_;  // padded_: the DFT's size, zero outside the thumbnail
  int since_moved_ = kHoldFrames;                            // frames since the camera last moved
  double shift_ = 0.0;
  bool new_scene_ = false;
  double lambdas_[kToneFrames] = {};  // the last frames' lambda, a ring; lambda_count_ of them valid
  int lambda_count_ = 0, lambda_next_ = 0;
};

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_CAMERA_MOTION_H
