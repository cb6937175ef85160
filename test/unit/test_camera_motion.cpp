// CameraMotion: a still camera is judged still whatever its light does, a moving one moving; the
// stream's extractors (cv::Feature2D adapter, ORB-SLAM adapter, the evaluation) follow the judgment.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/enhance.h"
#include "enhanced_orb/evaluation/sequence.h"
#include "enhanced_orb/feature2d.h"
#include "enhanced_orb/orb_extractor.h"
#include "enhanced_orb/orb_slam_extractor.h"
#include "test_images.h"

namespace enhanced_orb {
namespace {

// The view of `scene` seen from (x, y) (sub-pixel), 640 x 480.
cv::Mat view(const cv::Mat& scene, double x, double y) {
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, -x, 0, 1, -y);
  cv::Mat out;
  cv::warpAffine(scene, out, shift, cv::Size(640, 480), cv::INTER_LINEAR, cv::BORDER_REFLECT);
  return out;
}

// `image` x `light` with Gaussian noise of `sigma`.
cv::Mat underLight(const cv::Mat& image, double light, double sigma, cv::RNG& rng) {
  cv::Mat f;
  image.convertTo(f, CV_32F, light);
  cv::Mat noise(image.size(), CV_32F);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, sigma);
  f += noise;
  cv::Mat out;
  f.convertTo(out, CV_8U);
  return out;
}

const cv::Mat& scene() {
  static const cv::Mat s = test::syntheticScene(cv::Size(1200, 900), 600);
  return s;
}

#define REQUIRE_FRAMES(frames, dir) REQUIRE_SHARED_DATA(!(frames).empty(), std::string("frames under ") + (dir))

// `p` with a moving camera's tone curve decided by the stream's quality test (moving_gamma_mode
// auto) instead of the default's none.
Params qualityTested(Params p = Params()) {
  p.enhance.moving_gamma_mode = GammaMode::kAuto;
  return p;
}

TEST(CameraMotion, MeasuresTheShiftOfTheView) {
  for (double dx : {5.0, 12.0, 40.0, -25.0}) {
    CameraMotion motion;
    EXPECT_FALSE(motion.update(view(scene(), 200, 200)));  // a stream's first frame: still
    EXPECT_DOUBLE_EQ(motion.shift(), 0.0);
    EXPECT_TRUE(motion.update(view(scene(), 200 + dx, 200 + dx / 2))) << dx;
    EXPECT_NEAR(motion.shift(), std::hypot(dx, dx / 2), 1.0) << dx;
  }
}

TEST(CameraMotion, AStillCameraStaysStillWhateverItsLight) {
  cv::RNG rng(5);
  CameraMotion motion;
  const cv::Mat still = view(scene(), 300, 200);
  // Noise, a darkening to a tenth with strong noise, flicker, an overexposure: no shift.
  const double lights[] = {1.0, 1.0, 0.1, 0.1, 1.0, 0.5, 1.0, 0.5, 2.5, 1.0};
  for (double light : lights) {
    EXPECT_FALSE(motion.update(underLight(still, light, light < 0.5 ? 4.0 : 2.0, rng))) << light;
    EXPECT_LT(motion.shift(), 1.0) << light;
  }
}

TEST(CameraMotion, ASlowCameraIsMovingAllAlongAndAStoppedOneStillAfterTheHold) {
  CameraMotion motion;
  double x = 100.0;
  int first_moving = -1;
  // 0.5 px a frame: under the moved threshold from frame to frame, over it within a few frames.
  for (int i = 0; i < 60; ++i, x += 0.5) {
    if (motion.update(view(scene(), x, 150)) && first_moving < 0) {
      first_moving = i;
    }
    if (first_moving >= 0) {
      EXPECT_TRUE(motion.moving()) << "frame " << i;  // once moving, the hold covers the gaps
    }
  }
  ASSERT_GE(first_moving, 1);
  EXPECT_LE(first_moving, 12);
  // Stopped: still again within kHoldFrames frames of its last move, and then for good.
  int still_after = 0;
  while (motion.update(view(scene(), x, 150)) && still_after < 2 * CameraMotion::kHoldFrames) {
    ++still_after;
  }
  EXPECT_GE(still_after, 1);
  EXPECT_LT(still_after, CameraMotion::kHoldFrames);
  for (int i = 0; i < 5; ++i) {
    EXPECT_FALSE(motion.update(view(scene(), x, 150)));
  }
}

TEST(CameraMotion, BadFramesChangeNothingAndANewSizeStartsANewStream) {
  CameraMotion motion;
  motion.update(view(scene(), 0, 0));
  ASSERT_TRUE(motion.update(view(scene(), 30, 0)));
  // Not judged: empty, colour, 16-bit. The judgment stays.
  EXPECT_TRUE(motion.update(cv::Mat()));
  EXPECT_TRUE(motion.update(cv::Mat(480, 640, CV_8UC3, cv::Scalar(1, 2, 3))));
  EXPECT_TRUE(motion.update(cv::Mat(480, 640, CV_16UC1, cv::Scalar(1000))));
  // Another size: a new stream, whose first frame is still.
  EXPECT_FALSE(motion.update(cv::Mat(240, 320, CV_8UC1, cv::Scalar(9))));
  EXPECT_FALSE(motion.update(cv::Mat(240, 320, CV_8UC1, cv::Scalar(200))));  // constant frames: no shift
  EXPECT_DOUBLE_EQ(motion.shift(), 0.0);
  // Too small to judge (thumbnail under kMinThumbnail): still, whatever it shows.
  cv::RNG rng(1);
  for (int i = 0; i < 5; ++i) {
    cv::Mat tiny(12, 9, CV_8UC1);
    rng.fill(tiny, cv::RNG::UNIFORM, 0, 256);
    EXPECT_FALSE(motion.update(tiny));
  }
  // reset(): the next frame is a first one.
  motion.update(view(scene(), 0, 0));
  ASSERT_TRUE(motion.update(view(scene(), 30, 0)));
  motion.reset();
  EXPECT_FALSE(motion.moving());
  EXPECT_FALSE(motion.update(view(scene(), 90, 0)));
}

// A SLAM front end's stream starts moving: its first frame is judged moving, the next ones by their
// shift as any stream's; a new size starts it anew, a frame too small to judge keeps the start.
TEST(CameraMotion, AStreamThatStartsMovingIsJudgedByItsSecondFrame) {
  for (bool camera_moves : {false, true}) {
    CameraMotion motion(CameraMotion::Start::kMoving);
    EXPECT_EQ(motion.start(), CameraMotion::Start::kMoving);
    EXPECT_TRUE(motion.moving());
    EXPECT_TRUE(motion.update(view(scene(), 200, 200)));
    EXPECT_EQ(motion.update(view(scene(), camera_moves ? 230 : 200, 200)), camera_moves);
    EXPECT_EQ(motion.update(view(scene(), camera_moves ? 260 : 200, 200)), camera_moves);
  }
  CameraMotion motion(CameraMotion::Start::kMoving);
  motion.update(view(scene(), 0, 0));
  EXPECT_FALSE(motion.update(view(scene(), 0, 0)));
  EXPECT_TRUE(motion.update(cv::Mat(240, 320, CV_8UC1, cv::Scalar(9))));  // another size: a first frame
  EXPECT_FALSE(motion.update(cv::Mat(240, 320, CV_8UC1, cv::Scalar(9))));
  for (int i = 0; i < 3; ++i) {
    EXPECT_TRUE(motion.update(cv::Mat(12, 9, CV_8UC1, cv::Scalar(i))));  // never judged: the start
  }
  motion.reset();
  EXPECT_TRUE(motion.moving());
  // A copy starts its streams as the original does.
  const CameraMotion copy = motion;
  EXPECT_EQ(copy.start(), CameraMotion::Start::kMoving);
  EXPECT_EQ(CameraMotion().start(), CameraMotion::Start::kStill);
}

// The shared frames of a static camera (V1_01 excerpt) are judged still under every light
// condition of the sequence evaluation, raw and enhanced (as ExtractNodelet sees them after
// EnhanceNodelet); those of a hand-carried camera (MH_01 excerpt) moving from the second frame on.
TEST(CameraMotion, SharedFramesOfAStillAndAMovingCamera) {
  // Every third still frame (32), the first 45 moving ones: the judgment at each. The sensor model
  // is slow under an emulator: ENHANCED_ORB_IDENTITY_STRIDE (the aarch64 job) takes fewer.
  const char* stride_env = std::getenv("ENHANCED_ORB_IDENTITY_STRIDE");
  const size_t stride = stride_env && std::atoi(stride_env) > 1 ? static_cast<size_t>(std::atoi(stride_env)) : 1;
  const std::vector<cv::Mat> still = test::cam0Frames(ENHANCED_ORB_EUROC_DIR, 3 * stride);
  REQUIRE_FRAMES(still, ENHANCED_ORB_EUROC_DIR);
  const std::vector<cv::Mat> moving = test::cam0Frames(ENHANCED_ORB_MOVING_DIR, 1, std::max<size_t>(10, 45 / stride));
  REQUIRE_FRAMES(moving, ENHANCED_ORB_MOVING_DIR);
  const int n_moving = static_cast<int>(moving.size());
  const OrbExtractor enhancing;
  for (const evaluation::LightCondition& light : evaluation::lightConditions()) {
    std::vector<cv::Mat> raw, enhanced, walked;
    for (size_t i = 0; i < still.size(); ++i) {
      raw.push_back(light.apply(still[i], static_cast<int>(i), static_cast<int>(still.size()), 100 + i));
      enhanced.push_back(enhancing.extract(raw.back()).image);
    }
    for (int i = 0; i < n_moving; ++i) {
      walked.push_back(light.apply(moving[i], i, n_moving, 500 + i));
    }
    const auto moving_count = [](const std::vector<StreamJudgment>& judged, size_t from) {
      return std::count_if(judged.begin() + from, judged.end(), [](const StreamJudgment& j) { return j.moving; });
    };
    for (const std::vector<cv::Mat>* frames : {&raw, &enhanced}) {
      EXPECT_EQ(moving_count(evaluation::judgeMotion(*frames), 0), 0)
          << light.name << (frames == &raw ? ", raw" : ", enhanced");
    }
    const std::vector<StreamJudgment> judged = evaluation::judgeMotion(walked);
    EXPECT_FALSE(judged[0].moving) << light.name;
    EXPECT_EQ(moving_count(judged, 1), n_moving - 1) << light.name;
  }
}

// The PNG images under a folder, its subfolders' too, sorted by path as a user lists them.
std::vector<std::filesystem::path> imagesIn(const std::filesystem::path& dir) {
  std::vector<std::filesystem::path> paths;
  if (std::filesystem::is_directory(dir)) {
    for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
      if (entry.path().extension() == ".png") {
        paths.push_back(entry.path());
      }
    }
  }
  std::sort(paths.begin(), paths.end());
  return paths;
}

// A folder of unrelated scenes, each shot several times from one place (the lighting sets sorted
// by name, as a user passes them to enhanced_orb_extract): every change of scene is a new scene,
// never motion, so no image of them is judged moving; within a scene no image is a new scene.
TEST(CameraMotion, ANewSceneStartsANewStreamInsteadOfCountingAsMotion) {
  const std::string root = ENHANCED_ORB_SHARED_DATA "/lighting";
  size_t images = 0, changes = 0;
  for (const char* set : {"exposure_hdrps", "exposure_duth", "exposure_memorial", "webcam"}) {
    const std::vector<std::filesystem::path> paths = imagesIn(root + "/" + set);
    CameraMotion motion;
    cv::Size last_size;
    std::filesystem::path last_scene;
    for (const std::filesystem::path& path : paths) {
      const cv::Mat image = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
      ASSERT_FALSE(image.empty()) << path;
      const bool moving = motion.update(image);
      const bool same_size = image.size() == last_size;
      EXPECT_FALSE(moving) << path;
      if (!last_scene.empty() && same_size) {
        const bool other_scene = path.parent_path() != last_scene;
        EXPECT_EQ(motion.newScene(), other_scene) << path << " after an image of " << last_scene;
        changes += other_scene;
      }
      last_size = image.size();
      last_scene = path.parent_path();
      ++images;
    }
  }
  if (images == 0) {
    std::vector<cv::Mat> none;
    REQUIRE_FRAMES(none, root);
  }
  EXPECT_GE(changes, 15u);  // scene changes between images of one size: the test has teeth
}

// Frames of two cameras interleaved (a camera switch at every frame): each switch is a new scene,
// and the still camera's frames stay judged still; a moving camera's frames, indoors at 20 Hz or
// driving at 10 Hz, are never a new scene. A car driving straight zooms the view more than it
// shifts it: it is judged moving within its first second and from then on.
TEST(CameraMotion, CamerasSwitchedAreNewScenesAndDrivingIsMotion) {
  const std::vector<cv::Mat> still = test::cam0Frames(ENHANCED_ORB_EUROC_DIR, 10);
  REQUIRE_FRAMES(still, ENHANCED_ORB_EUROC_DIR);
  const std::vector<cv::Mat> moving = test::cam0Frames(ENHANCED_ORB_MOVING_DIR, 30);
  REQUIRE_FRAMES(moving, ENHANCED_ORB_MOVING_DIR);
  CameraMotion switched;
  for (size_t i = 0; i < std::min(still.size(), moving.size()); ++i) {
    EXPECT_FALSE(switched.update(still[i])) << i;
    EXPECT_EQ(switched.newScene(), i > 0) << i;
    EXPECT_FALSE(switched.update(moving[i])) << i;
    EXPECT_TRUE(switched.newScene()) << i;
  }
  for (const char* excerpt : {"straight_51", "turn_51"}) {
    const std::string dir = std::string(ENHANCED_ORB_SHARED_DATA "/kitti/") + excerpt + "/image_0";
    std::vector<cv::Mat> frames;
    for (const std::filesystem::path& path : imagesIn(dir)) {
      frames.push_back(cv::imread(path.string(), cv::IMREAD_GRAYSCALE));
    }
    REQUIRE_FRAMES(frames, dir);
    for (const evaluation::LightCondition& light : evaluation::lightConditions()) {
      CameraMotion motion;
      int first_moving = -1, still_after = 0, new_scenes = 0;
      for (size_t i = 0; i < frames.size(); ++i) {
        const cv::Mat frame =
            light.apply(frames[i], static_cast<int>(i), static_cast<int>(frames.size()), 900 + static_cast<int>(i));
        const bool moving = motion.update(frame);
        if (moving && first_moving < 0) {
          first_moving = static_cast<int>(i);
        }
        still_after += !moving && first_moving >= 0;
        new_scenes += motion.newScene();
      }
      EXPECT_EQ(new_scenes, 0) << excerpt << ", " << light.name;
      EXPECT_GE(first_moving, 1) << excerpt << ", " << light.name;
      EXPECT_LE(first_moving, 10) << excerpt << ", " << light.name;
      EXPECT_EQ(still_after, 0) << excerpt << ", " << light.name;
    }
  }
}

// With camera_motion auto, a frame judged moving gets exactly the moving selection (the motion
// preset's keypoints), one judged still the still one; the adapters judge the frames they are given.
TEST(CameraMotion, ExtractorsFollowTheJudgment) {
  const cv::Mat first = view(scene(), 100, 100), second = view(scene(), 140, 110);
  const OrbExtractor automatic, moving_only(Params::motion());
  ExtractOptions judged_moving;
  judged_moving.camera_moving = true;
  Extraction a, m;
  automatic.extract(second, judged_moving, a);
  moving_only.extract(second, m);
  EXPECT_TRUE(a.camera_moving && m.camera_moving);
  ASSERT_EQ(a.keypoints.size(), m.keypoints.size());
  EXPECT_EQ(cv::norm(a.descriptors, m.descriptors, cv::NORM_INF), 0.0);
  const Extraction s = automatic.extract(second);
  EXPECT_FALSE(s.camera_moving);
  const bool same =
      s.keypoints.size() == m.keypoints.size() && cv::norm(s.descriptors, m.descriptors, cv::NORM_INF) == 0.0;
  EXPECT_FALSE(same) << "the two selections differ on this scene";

  // cv::Feature2D: the second image of a moving stream gets the moving selection; clear() starts anew.
  cv::Ptr<ORB> orb = ORB::create();
  std::vector<cv::KeyPoint> keypoints;
  cv::Mat descriptors;
  orb->detectAndCompute(first, cv::noArray(), keypoints, descriptors);
  orb->detectAndCompute(second, cv::noArray(), keypoints, descriptors);
  EXPECT_EQ(cv::norm(descriptors, m.descriptors, cv::NORM_INF), 0.0);
  orb->clear();
  orb->detectAndCompute(second, cv::noArray(), keypoints, descriptors);
  EXPECT_EQ(cv::norm(descriptors, s.descriptors, cv::NORM_INF), 0.0);

  // The stream's call judges, then extracts: the same as the two steps, with the judgment timed as
  // a stage of its own, part of the call's total; a mode that does not judge leaves the stream alone.
  CameraMotion motion;
  ExtractOptions options;
  Extraction streamed;
  automatic.extract(first, motion, options, streamed);
  EXPECT_FALSE(options.camera_moving);
  automatic.extract(second, motion, options, streamed);
  EXPECT_TRUE(options.camera_moving && streamed.camera_moving);
  EXPECT_EQ(cv::norm(streamed.descriptors, m.descriptors, cv::NORM_INF), 0.0);
  EXPECT_GT(streamed.timings.judge_ms, 0.0);
  EXPECT_DOUBLE_EQ(streamed.timings.overlap_ms, 0.0);  // one thread: one stage after the other
  EXPECT_DOUBLE_EQ(streamed.timings.totalMs(), streamed.timings.convert_ms + streamed.timings.judge_ms +
                                                   streamed.timings.enhance_ms + streamed.timings.extract_ms);
  const OrbExtractor still_only(Params::baseline());
  CameraMotion unused;
  still_only.extract(first, unused, options, streamed);
  still_only.extract(second, unused, options, streamed);
  EXPECT_FALSE(options.camera_moving);
  EXPECT_EQ(unused.shift(), 0.0);  // never fed: no frame judged
  // The adapter's times cover its whole call: a colour image's conversion too.
  cv::Mat colour;
  cv::cvtColor(second, colour, cv::COLOR_GRAY2BGR);
  orb->clear();
  orb->detectAndCompute(colour, cv::noArray(), keypoints, descriptors);
  EXPECT_GT(orb->timings().convert_ms, 0.0);
  EXPECT_GT(orb->timings().judge_ms, 0.0);
  EXPECT_GE(orb->timings().totalMs(), orb->timings().enhance_ms + orb->timings().extract_ms);

  // ORB-SLAM's extractor, settings as the default mode's: the same, except that its first frame
  // already counts as a moving camera's (its map starts from the first frames).
  OrbSlamExtractor slam(1000, 1.2f, 8, 20, 7, Params());
  std::vector<int> lapping;  // none: the keypoints in the extractor's order
  slam(first, cv::noArray(), keypoints, descriptors, lapping);
  const Extraction m_first = moving_only.extract(first);
  ASSERT_EQ(keypoints.size(), m_first.keypoints.size());
  EXPECT_EQ(cv::norm(descriptors, m_first.descriptors, cv::NORM_INF), 0.0);
  slam(second, cv::noArray(), keypoints, descriptors, lapping);
  ASSERT_EQ(keypoints.size(), m.keypoints.size());
  EXPECT_EQ(cv::norm(descriptors, m.descriptors, cv::NORM_INF), 0.0);
}

// With two threads a stream's frame is enhanced while it is judged, as the last frame's judgment
// would have it: the same results as one thread, frame by frame, where the judgment changes (the
// camera starts and stops, the light flickers across the quality test, the scene changes) too.
TEST(CameraMotion, TwoThreadsEnhanceWhileJudgingWithTheResultsOfOne) {
  cv::RNG rng(5);
  std::vector<cv::Mat> frames;
  for (int i = 0; i < 4; ++i) {  // still
    frames.push_back(underLight(view(scene(), 50, 50), 0.4, 1.5, rng));
  }
  for (int i = 0; i < 14; ++i) {  // moving: dim frames, contrasty ones (the curve turns on), dim again
    cv::Mat f = view(scene(), 50 + 8.0 * i, 50 + 3.0 * i);
    if (i >= 4 && i <= 11) {
      f.convertTo(f, CV_8U, 3.0, -250.0);
    } else {
      f = underLight(f, 0.4, 1.5, rng);
    }
    frames.push_back(f);
  }
  frames.push_back(test::syntheticScene(cv::Size(640, 480), 77));  // another scene
  for (int i = 0; i < 3; ++i) {
    frames.push_back(frames.back().clone());
  }
  const Params one_thread = qualityTested();  // the stream's quality test decides the curve
  Params two_threads = one_thread;
  two_threads.orb.threads = two_threads.enhance.threads = 2;
  const OrbExtractor a(one_thread), b(two_threads);
  CameraMotion motion_a, motion_b;
  ExtractOptions options_a, options_b;
  Extraction out_a, out_b;
  int curve_changes = 0;
  bool last_poor = false;
  for (size_t i = 0; i < frames.size(); ++i) {
    a.extract(frames[i], motion_a, options_a, out_a);
    b.extract(frames[i], motion_b, options_b, out_b);
    EXPECT_EQ(out_a.camera_moving, out_b.camera_moving) << i;
    EXPECT_EQ(out_a.poor_quality, out_b.poor_quality) << i;
    EXPECT_EQ(cv::norm(out_a.image, out_b.image, cv::NORM_INF), 0.0) << i;
    ASSERT_EQ(out_a.keypoints.size(), out_b.keypoints.size()) << i;
    EXPECT_EQ(cv::norm(out_a.descriptors, out_b.descriptors, cv::NORM_INF), 0.0) << i;
    EXPECT_GE(out_b.timings.overlap_ms, 0.0);
    EXPECT_LE(out_b.timings.overlap_ms, std::min(out_b.timings.judge_ms, out_b.timings.enhance_ms) + 1e-9);
    curve_changes += i > 0 && out_b.poor_quality != last_poor;
    last_poor = out_b.poor_quality;
  }
  EXPECT_GE(curve_changes, 3) << "the stream changes the quality test's outcome";
}

// A moving camera's frame is enhanced with moving_gamma_mode (never by default; auto: the paper's
// quality test), a still camera's with gamma_mode (always): a dim, flat frame gets the tone curve
// only when still, a contrasty one both ways with auto and only when still by default.
TEST(CameraMotion, AMovingCamerasFrameGetsTheToneCurveByItsMode) {
  cv::RNG rng(7);
  const cv::Mat dim = underLight(view(scene(), 10, 10), 0.25, 1.5, rng);
  ASSERT_LE(imageLambda(dim), Params().enhance.std_threshold);  // not poor by the paper's test
  const OrbExtractor automatic;
  ExtractOptions moving;
  moving.camera_moving = true;
  Extraction still_frame, moving_frame;
  automatic.extract(dim, still_frame);
  automatic.extract(dim, moving, moving_frame);
  EXPECT_FALSE(still_frame.camera_moving);
  EXPECT_TRUE(moving_frame.camera_moving);
  // The still frame's tone curve stretched the dim tones; the moving frame's image is the filtered
  // frame only, as with gamma_mode never.
  EnhanceParams never = Params().enhance;
  never.gamma_mode = GammaMode::kNever;
  EXPECT_EQ(cv::norm(moving_frame.image, enhance(dim, never).image, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(still_frame.image, moving_frame.image, cv::NORM_INF), 20.0);
  // moving_gamma_mode always: the same image as a still camera's.
  Params always;
  always.enhance.moving_gamma_mode = GammaMode::kAlways;
  Extraction curved;
  OrbExtractor(always).extract(dim, moving, curved);
  EXPECT_EQ(cv::norm(curved.image, still_frame.image, cv::NORM_INF), 0.0);
  // A contrasty frame is poor by the paper's test: with moving_gamma_mode auto the curve runs for a
  // moving camera too; by default it does not.
  cv::Mat contrasty;
  view(scene(), 10, 10).convertTo(contrasty, CV_8U, 3.0, -250.0);
  ASSERT_GT(imageLambda(contrasty), Params().enhance.std_threshold);
  Extraction a, b, c;
  automatic.extract(contrasty, a);
  OrbExtractor(qualityTested()).extract(contrasty, moving, b);
  EXPECT_EQ(cv::norm(a.image, b.image, cv::NORM_INF), 0.0);
  automatic.extract(contrasty, moving, c);
  EXPECT_EQ(cv::norm(c.image, enhance(contrasty, never).image, cv::NORM_INF), 0.0);
  EXPECT_GT(cv::norm(a.image, c.image, cv::NORM_INF), 10.0);
}

// A moving camera's frames are enhanced alike: with moving_gamma_mode auto the quality test reads
// the least lambda of the stream's last kToneFrames frames. A contrasty frame between dim ones
// (flickering light) gets no curve, as they do; once kToneFrames contrasty frames have passed it
// gets it, as a still frame would.
TEST(CameraMotion, AMovingCamerasFramesAreEnhancedAlike) {
  const double threshold = Params().enhance.std_threshold;
  cv::RNG rng(11);
  const auto frame = [&](int i, bool contrasty) {
    cv::Mat f = view(scene(), 6.0 * i, 3.0 * i);
    if (contrasty) {
      f.convertTo(f, CV_8U, 3.0, -250.0);
    } else {
      f = underLight(f, 0.4, 1.5, rng);
    }
    return f;
  };
  CameraMotion motion;
  EXPECT_DOUBLE_EQ(motion.streamLambda(), -1.0);
  const OrbExtractor extractor(qualityTested());
  ExtractOptions options;
  Extraction out;
  int i = 0;
  // Flicker: dim and contrasty frames in turn, the camera moving.
  for (; i < 12; ++i) {
    const cv::Mat f = frame(i, i % 2 == 0);  // the last one dim
    extractor.extract(f, motion, options, out);
    EXPECT_NEAR(out.lambda, imageLambda(f), 1e-12);
    if (i >= 2) {
      ASSERT_TRUE(out.camera_moving) << i;
      EXPECT_LE(options.stream_lambda, threshold) << i;
      EXPECT_FALSE(out.poor_quality) << "frame " << i << ", lambda " << out.lambda;
    }
  }
  ASSERT_GT(imageLambda(frame(i, true)), threshold);
  // Then contrasty frames only: the curve from the kToneFrames-th on.
  for (int k = 1; k <= 2 * CameraMotion::kToneFrames; ++i, ++k) {
    extractor.extract(frame(i, true), motion, options, out);
    ASSERT_TRUE(out.camera_moving) << i;
    EXPECT_EQ(out.poor_quality, k >= CameraMotion::kToneFrames) << "contrasty frame " << k;
  }
  // What the tool reports is the decision made: the same image as gamma_mode always gives.
  const cv::Mat last = frame(i - 1, true);
  EnhanceParams always = Params().enhance;
  always.gamma_mode = GammaMode::kAlways;
  EXPECT_EQ(cv::norm(out.image, enhance(last, always).image, cv::NORM_INF), 0.0);
  // A new stream forgets the lambdas.
  motion.reset();
  EXPECT_DOUBLE_EQ(motion.streamLambda(), -1.0);
  motion.update(last);
  EXPECT_DOUBLE_EQ(motion.streamLambda(), imageLambda(last));
  // camera_motion moving (the motion preset) with moving_gamma_mode auto reads the stream's lambda
  // too: a contrasty frame after dim ones gets no curve.
  const OrbExtractor motion_preset(qualityTested(Params::motion()));
  CameraMotion stream;
  for (int k = 0; k < 3; ++k) {
    motion_preset.extract(frame(k, false), stream, options, out);
  }
  motion_preset.extract(frame(3, true), stream, options, out);
  EXPECT_TRUE(out.camera_moving);
  EXPECT_FALSE(out.poor_quality);
  // A still camera's frame ignores the stream's lambda (gamma_mode always).
  ExtractOptions still;
  still.stream_lambda = 0.0;
  extractor.extract(frame(0, false), still, out);
  EXPECT_TRUE(out.poor_quality);
}

}  // namespace
}  // namespace enhanced_orb
