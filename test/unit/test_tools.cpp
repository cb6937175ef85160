// The command-line tools as a user runs them: outputs that would collide or overwrite an input are
// refused before anything is written, oversized images are refused from their header, one bad
// frame is skipped, static frame pairs are excluded, errors name file, line and value, and nothing
// half-written is left behind.
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <sys/wait.h>
#include <unistd.h>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "enhanced_orb/evaluation/sequence.h"

#include "test_images.h"

namespace fs = std::filesystem;
namespace test = enhanced_orb::test;

namespace {

struct Outcome {
  int code = -1;
  std::string output;  // stdout and stderr
};

Outcome run(const std::string& command) {
  Outcome r;
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  if (!pipe) {
    return r;
  }
  std::array<char, 4096> buffer{};
  while (fgets(buffer.data(), buffer.size(), pipe)) {
    r.output += buffer.data();
  }
  const int status = pclose(pipe);
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return r;
}

// A test that reads this file of the shared data.
#define NEEDS_DATA(path) REQUIRE_SHARED_DATA(fs::exists(path), std::string(path))

class Tools : public ::testing::Test {
protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("enhanced_orb_tools_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string image(const std::string& relative, cv::Size size = cv::Size(160, 120)) {
    const fs::path path = dir_ / relative;
    fs::create_directories(path.parent_path());
    cv::imwrite(path.string(), test::syntheticScene(size, 20));
    return path.string();
  }
  // A PNG whose header announces width x height, with no pixel data behind it.
  std::string pngHeader(const std::string& relative, std::uint32_t width, std::uint32_t height) {
    const fs::path path = dir_ / relative;
    std::ofstream out(path, std::ios::binary);
    const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    out.write(reinterpret_cast<const char*>(sig), 8);
    const unsigned char ihdr[8] = {0, 0, 0, 13, 'I', 'H', 'D', 'R'};
    out.write(reinterpret_cast<const char*>(ihdr), 8);
    for (std::uint32_t v : {width, height}) {
      const unsigned char be[4] = {static_cast<unsigned char>(v >> 24), static_cast<unsigned char>(v >> 16),
                                   static_cast<unsigned char>(v >> 8), static_cast<unsigned char>(v)};
      out.write(reinterpret_cast<const char*>(be), 4);
    }
    const unsigned char rest[5] = {8, 0, 0, 0, 0};
    out.write(reinterpret_cast<const char*>(rest), 5);
    return path.string();
  }
  // A small ASL sequence: cam0 with `frames` images, imu0 with two samples; `csv_line` replaces
  // the cam0 data.csv content when given.
  fs::path asl(int frames, const std::string& csv = "") {
    const fs::path mav0 = dir_ / "seq" / "mav0";
    fs::create_directories(mav0 / "cam0" / "data");
    fs::create_directories(mav0 / "imu0");
    std::ofstream list(mav0 / "cam0" / "data.csv");
    list << "#timestamp [ns],filename\n";
    for (int i = 0; i < frames; ++i) {
      const std::string name = std::to_string(1000 + i) + ".png";
      cv::imwrite((mav0 / "cam0" / "data" / name).string(), test::syntheticScene(cv::Size(160, 120), i));
      if (csv.empty()) {
        list << 1000 + i << "," << name << "\n";
      }
    }
    list << csv;
    std::ofstream imu(mav0 / "imu0" / "data.csv");
    imu << "#timestamp,w_x,w_y,w_z,a_x,a_y,a_z\n1000,0,0,0,0,0,9.8\n1001,0,0,0,0,0,9.8\n";
    return mav0.parent_path();
  }
  std::string quoted(const fs::path& p) const { return "'" + p.string() + "'"; }

  fs::path dir_;
};

const std::string kExtract = ENHANCED_ORB_EXTRACT_TOOL;
const std::string kEurocToBag = ENHANCED_ORB_EUROC_TO_BAG_TOOL;
const std::string kCompare = ENHANCED_ORB_COMPARE_TOOL;

}  // namespace

TEST_F(Tools, ExtractRefusesCollidingOutputsBeforeWritingAnything) {
  const std::string a = image("a/x.png"), b = image("b/x.png"), c = image("b/x.jpg");
  const Outcome r = run(kExtract + " " + a + " " + b + " " + c + " --output " + quoted(dir_ / "out"));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("would both write"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// A data set's layout, <scene>/<image>, its names repeating in every scene: each scene's results
// go to a folder of its own, named below the images' common folder.
TEST_F(Tools, ExtractKeepsTheFoldersOfImagesWhoseNamesRepeat) {
  const std::string a = image("set/a/00.png"), b = image("set/b/00.png"), c = image("set/b/01.png");
  const Outcome r = run(kExtract + " " + a + " " + b + " " + c + " --output " + quoted(dir_ / "out"));
  EXPECT_EQ(r.code, 0) << r.output;
  for (const char* written : {"a/00.yml", "b/00.yml", "b/01.yml"}) {
    EXPECT_TRUE(fs::exists(dir_ / "out" / written)) << written << "\n" << r.output;
  }
  EXPECT_FALSE(fs::exists(dir_ / "out" / "00.yml"));
}

TEST_F(Tools, ExtractRefusesToOverwriteAnInput) {
  const std::string x = image("d/x.png"), xe = image("d/x_enhanced.png");
  const auto before = fs::file_size(xe);
  const Outcome r = run(kExtract + " --save-enhanced " + x + " " + xe + " --output " + quoted(dir_ / "d"));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_NE(r.output.find("would overwrite the input"), std::string::npos) << r.output;
  EXPECT_EQ(fs::file_size(xe), before);
}

TEST_F(Tools, ExtractRefusesOversizedImagesFromTheHeaderAndGoesOn) {
  const std::string huge = pngHeader("huge.png", 16000, 16000);
  const std::string good = image("good.png");
  Outcome r = run(kExtract + " " + huge + " " + good + " --output " + quoted(dir_ / "out"));
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("16000 x 16000"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "out" / "good.yml"));
  EXPECT_FALSE(fs::exists(dir_ / "out" / "huge.yml"));
  r = run(kExtract + " --max-pixels 100 " + good + " --output " + quoted(dir_ / "small"));
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("160 x 120"), std::string::npos) << r.output;
  for (const auto& entry : fs::directory_iterator(dir_ / "out")) {
    EXPECT_EQ(entry.path().filename().string().find(".part"), std::string::npos) << entry.path();
  }
}

TEST_F(Tools, ExtractOptionParsing) {
  const std::string good = image("good.png");
  const std::string tail = " " + good + " --output " + quoted(dir_ / "out");
  for (const char* bad : {"--c-min nan", "--alpha inf", "--alpha -0.5", "--max-features 1e9", "--c-min 12.5",
                          "--max-features 200000", "--preset fast", "--no-such-option 1", "--max-pixels 0"}) {
    const Outcome r = run(kExtract + " " + bad + tail);
    EXPECT_EQ(r.code, 2) << bad << ": " << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out" / "good.yml")) << bad;
  }
  // A repeated option: the last one wins.
  auto count = [](const std::string& out) { return std::stoi(out.substr(out.find(": ") + 2)); };
  const Outcome last = run(kExtract + " --max-features 50 --max-features 20" + tail);
  const Outcome once = run(kExtract + " --max-features 20" + tail);
  const Outcome fifty = run(kExtract + " --max-features 50" + tail);
  ASSERT_EQ(last.code, 0) << last.output;
  EXPECT_EQ(count(last.output), count(once.output)) << last.output << once.output;
  EXPECT_LT(count(last.output), count(fifty.output)) << last.output << fifty.output;
  const Outcome help = run(kExtract + " --help");
  EXPECT_EQ(help.code, 0);
  EXPECT_NE(help.output.find("exit codes"), std::string::npos);
}

TEST_F(Tools, ComparePaperSkipsOneBadFrameAndKeepsTheRest) {
  for (int i = 0; i < 3; ++i) {
    image("frames/f" + std::to_string(i) + ".png");
  }
  image("frames/f9_thin.png", cv::Size(1, 60));
  const Outcome r = run(kCompare + " --paper --images " + quoted(dir_ / "frames") +
                        " --every 1 --budgets 1000 --output " + quoted(dir_ / "out"));
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("f9_thin.png"), std::string::npos) << r.output;
  std::ifstream frames(dir_ / "out" / "frames.csv");
  int rows = 0;
  for (std::string line; std::getline(frames, line);) {
    ++rows;
  }
  EXPECT_EQ(rows, 1 + 3 * 3);  // header, 3 frames x 3 methods
}

TEST_F(Tools, ComparePaperRefusesOptionsOfTheOtherMode) {
  image("frames/f0.png");
  const std::string images = " --images " + quoted(dir_ / "frames");
  for (const std::string& args : {images, " --paper" + images + " --euroc " + quoted(dir_),
                                  " --paper --bag " + quoted(dir_ / "x.bag"), " --paper" + images + " --lighting x"}) {
    const Outcome r = run(kCompare + args + " --output " + quoted(dir_ / "out"));
    EXPECT_EQ(r.code, 2) << args << "\n" << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << args;
  }
}

// The moving EuRoC excerpt as ETH ships it (sensor.yaml without a %YAML line): relative poses and
// stereo tracking for every method asked, with errors that show the evaluation works on real frames.
TEST_F(Tools, CompareRunsTheSequenceEvaluationOnEurocAsShipped) {
  EXPECT_EQ(run(kCompare + " --sequence x --conditions eclipse --output " + quoted(dir_ / "none")).code, 2);
  const std::string moving = ENHANCED_ORB_MOVING_DIR;
  NEEDS_DATA(moving + "/mav0/cam0/sensor.yaml");
  const fs::path out = dir_ / "seq";
  const Outcome r = run(kCompare + " --sequence " + moving + " --methods default,ORB-SLAM --budgets 500 " +
                        "--conditions unchanged --gaps 5 --sequence-every 10 --output " + quoted(out));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_EQ(r.output.find("no calibration"), std::string::npos) << r.output;
  auto fields = [](const std::string& text) {
    std::vector<std::string> f;
    std::istringstream in(text);
    for (std::string field; std::getline(in, field, ',');) {
      f.push_back(field);
    }
    return f;
  };
  std::map<std::string, std::vector<double>> errors;
  std::ifstream pose(out / "sequence_pose.csv");
  std::string line;
  std::getline(pose, line);
  EXPECT_EQ(line, "sequence,condition,method,budget,frame,gap,keypoints,matches,inliers,rotation_deg,translation_deg");
  while (std::getline(pose, line)) {
    const std::vector<std::string> f = fields(line);
    ASSERT_EQ(f.size(), 11u) << line;
    errors[f[2]].push_back(std::max(std::stod(f[9]), std::stod(f[10])));
  }
  for (const std::string& method : {"default", "ORB-SLAM"}) {
    std::vector<double>& e = errors[method];
    ASSERT_GE(e.size(), 25u) << method;  // a pair every 10th of 295 frames
    std::nth_element(e.begin(), e.begin() + e.size() / 2, e.end());
    EXPECT_LT(e[e.size() / 2], 10.0) << method;  // median pose error of real moving frames
  }
  std::ifstream tracking(out / "sequence_tracking.csv");
  int frames = 0, tracked = 0;
  std::getline(tracking, line);
  while (std::getline(tracking, line)) {
    const std::vector<std::string> f = fields(line);
    ASSERT_EQ(f.size(), 11u) << line;
    ++frames;
    tracked += f[2] == "default" && f[8] == "1";
  }
  EXPECT_EQ(frames, 2 * 299);
  EXPECT_GT(tracked, 250);  // in unchanged light nearly every frame is tracked
}

TEST_F(Tools, CompareWritesEachLightConditionAsAEurocFolder) {
  EXPECT_EQ(run(kCompare + " --write-sequence " + quoted(dir_ / "w")).code, 2);  // needs --sequence
  const std::string moving = ENHANCED_ORB_MOVING_DIR;
  NEEDS_DATA(moving + "/mav0/cam0/sensor.yaml");
  const fs::path out = dir_ / "frames";
  const Outcome r = run(kCompare + " --sequence " + moving + " --conditions unchanged,dip --write-sequence " +
                        quoted(out) + " --output " + quoted(dir_ / "not_written"));
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "not_written"));
  const enhanced_orb::evaluation::Sequence original = enhanced_orb::evaluation::readSequence(moving);
  const int n = static_cast<int>(original.frames.size());
  for (const std::string condition : {"unchanged", "dip"}) {
    // What was written reads back as the same sequence: frames, cameras, ground truth.
    const enhanced_orb::evaluation::Sequence written =
        enhanced_orb::evaluation::readSequence((out / condition).string());
    ASSERT_EQ(static_cast<int>(written.frames.size()), n) << condition;
    ASSERT_EQ(written.right_frames.size(), original.right_frames.size()) << condition;
    EXPECT_EQ(cv::norm(cv::Mat(written.poses[n / 2]), cv::Mat(original.poses[n / 2])), 0.0) << condition;
    std::ifstream times(out / condition / "times.txt");
    std::vector<std::string> stamps;
    for (std::string line; std::getline(times, line);) {
      stamps.push_back(line);
    }
    ASSERT_EQ(static_cast<int>(stamps.size()), n) << condition;
    EXPECT_EQ(stamps[7] + ".png", fs::path(original.frames[7]).filename().string());
  }
  // Unchanged light writes the frames as recorded; in the dip the middle frame is far darker.
  const enhanced_orb::evaluation::Sequence unchanged =
      enhanced_orb::evaluation::readSequence((out / "unchanged").string());
  const enhanced_orb::evaluation::Sequence dip = enhanced_orb::evaluation::readSequence((out / "dip").string());
  for (int i : {0, n / 2, n - 1}) {
    const cv::Mat a = cv::imread(original.frames[i], cv::IMREAD_GRAYSCALE);
    EXPECT_EQ(cv::norm(a, cv::imread(unchanged.frames[i], cv::IMREAD_GRAYSCALE), cv::NORM_INF), 0.0) << i;
    EXPECT_EQ(cv::norm(cv::imread(original.right_frames[i], cv::IMREAD_GRAYSCALE),
                       cv::imread(unchanged.right_frames[i], cv::IMREAD_GRAYSCALE), cv::NORM_INF),
              0.0)
        << i;
  }
  const cv::Scalar bright = cv::mean(cv::imread(original.frames[n / 2], cv::IMREAD_GRAYSCALE));
  const cv::Scalar dark = cv::mean(cv::imread(dip.frames[n / 2], cv::IMREAD_GRAYSCALE));
  EXPECT_LT(dark[0], 0.5 * bright[0]);
}

TEST_F(Tools, CompareSamplesTheStereoPairsAsAsked) {
  EXPECT_EQ(run(kCompare + " --stereo-every 0 --output " + quoted(dir_ / "none")).code, 2);
  EXPECT_EQ(run(kCompare + " --stereo-every x --output " + quoted(dir_ / "none")).code, 2);
  NEEDS_DATA(test::eurocDir() + "/mav0/cam1/data.csv");
  auto stereoFrames = [&](int every) {
    const fs::path out = dir_ / ("out" + std::to_string(every));
    const Outcome r = run(kCompare + " --euroc " + test::eurocDir() + " --methods default --budgets 500 " +
                          "--degradations none --every 1000 --steps 1 --pair-every 1000 --stereo-every " +
                          std::to_string(every) + " --output " + quoted(out));
    EXPECT_EQ(r.code, 0) << r.output;
    std::ifstream pairs(out / "euroc_pairs.csv");
    std::vector<int> frames;
    for (std::string line; std::getline(pairs, line);) {
      if (line.find(",stereo,") != std::string::npos) {
        frames.push_back(std::stoi(line.substr(0, line.find(','))));
      }
    }
    return frames;
  };
  // Every 30th of the 95 frames that have a ground-truth pose: a stereo pair at each.
  const std::vector<int> sparse = stereoFrames(30), dense = stereoFrames(15);
  ASSERT_GE(sparse.size(), 2u);
  for (int frame : sparse) {
    EXPECT_EQ(frame % 30, 0) << frame;
  }
  EXPECT_GT(dense.size(), sparse.size());
  for (int frame : dense) {
    EXPECT_EQ(frame % 15, 0) << frame;
  }
}

TEST_F(Tools, ComparePaperExcludesPairsWithoutMotion) {
  NEEDS_DATA(test::eurocDir() + "/mav0/state_groundtruth_estimate0/data.csv");
  const Outcome r = run(kCompare + " --paper --euroc " + test::eurocDir() + " --max-frames 40 --every 100 --steps 1 " +
                        "--pair-every 5 --budgets 1000 --output " + quoted(dir_ / "out"));
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream pairs(dir_ / "out" / "pairs.csv");
  std::string header, row;
  std::getline(pairs, header);
  ASSERT_NE(header.find("static_excluded"), std::string::npos) << header;
  ASSERT_TRUE(static_cast<bool>(std::getline(pairs, row)));
  // method,budget,steps,pairs,static_excluded,...: the excerpt's camera is static.
  std::stringstream fields(row);
  std::string method, budget, steps, scored, excluded;
  std::getline(fields, method, ',');
  std::getline(fields, budget, ',');
  std::getline(fields, steps, ',');
  std::getline(fields, scored, ',');
  std::getline(fields, excluded, ',');
  EXPECT_GT(std::stoi(excluded), 0) << row;
  EXPECT_EQ(row.find("nan"), std::string::npos) << row;
}

TEST_F(Tools, EurocToBagAcceptsSpacesAndCountsImages) {
  const fs::path seq = asl(3);
  fs::path csv = seq / "mav0" / "cam0" / "data.csv";
  std::ofstream(csv) << "#timestamp [ns], filename\n1000, 1000.png\n1001, 1001.png\n1002, 1002.png\n";
  const Outcome r = run(kEurocToBag + " " + quoted(seq) + " " + quoted(dir_ / "out.bag"));
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("/cam0/image_raw: 3 images"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir_ / "out.bag"));
}

TEST_F(Tools, EurocToBagNamesTheFileLineAndValueAndLeavesNoPartialBag) {
  const fs::path seq = asl(2, "1003,\n");
  std::ofstream(seq / "mav0" / "cam0" / "data.csv") << "#t,f\n1000,1000.png\nabc,1001.png\n";
  Outcome r = run(kEurocToBag + " " + quoted(seq) + " " + quoted(dir_ / "out.bag"));
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("data.csv:3"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("'abc'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "out.bag"));
  // Images fine, IMU broken after them: still no bag, and no temporary file.
  std::ofstream(seq / "mav0" / "cam0" / "data.csv") << "#t,f\n1000,1000.png\n1001,1001.png\n";
  std::ofstream(seq / "mav0" / "imu0" / "data.csv") << "#t\n1000,0,0,0,0,0,9.8\n1001,0,0,x,0,0,9.8\n";
  r = run(kEurocToBag + " " + quoted(seq) + " " + quoted(dir_ / "out.bag"));
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("imu0/data.csv:3"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "out.bag"));
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_EQ(entry.path().filename().string().find(".part"), std::string::npos) << entry.path();
  }
}

TEST_F(Tools, EurocToBagRefusesADirectoryAsDataCsvAndAnOutputThatIsAnInput) {
  fs::path seq = asl(2);
  const fs::path input = seq / "mav0" / "cam0" / "data" / "1000.png";
  const auto before = fs::file_size(input);
  Outcome r = run(kEurocToBag + " " + quoted(seq) + " " + quoted(input));
  EXPECT_EQ(r.code, 2) << r.output;
  EXPECT_EQ(fs::file_size(input), before);
  fs::remove(seq / "mav0" / "cam0" / "data.csv");
  fs::create_directories(seq / "mav0" / "cam0" / "data.csv");
  r = run(kEurocToBag + " " + quoted(seq) + " " + quoted(dir_ / "out.bag"));
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_NE(r.output.find("is not a file"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "out.bag"));
}
