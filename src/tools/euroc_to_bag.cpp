// euroc_to_bag: turns a EuRoC MAV dataset folder in ASL layout into a rosbag with the topics,
// types, frame ids and timestamps of EuRoC's own bags:
//   /cam0/image_raw, /cam1/image_raw  sensor_msgs/Image, mono8, frame_id cam0 / cam1
//   /imu0                             sensor_msgs/Imu, frame_id imu4
#include <cstdint>
#include <exception>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <ros/time.h>
#include <rosbag/bag.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/image_encodings.h>

#include "enhanced_orb/evaluation/dataset.h"
#include "enhanced_orb/evaluation/files.h"

namespace fs = std::filesystem;
namespace ev = enhanced_orb::evaluation;

namespace {

const char* const kUsage = R"(usage: euroc_to_bag ASL_DIR OUTPUT.bag

ASL_DIR is a EuRoC sequence folder (the one holding mav0/, or mav0/ itself) with mav0/cam0,
mav0/cam1 and mav0/imu0 (each optional, at least one present). Writes /cam0/image_raw,
/cam1/image_raw (sensor_msgs/Image mono8) and /imu0 (sensor_msgs/Imu) with the dataset's stamps.
The bag is written under a temporary name and renamed when complete: a failed run leaves nothing.
Images listed in a data.csv but absent are skipped with a warning; a malformed line, an
unreadable image or an output that is one of the inputs ends the run.
exit codes: 0 written, 1 an input is missing or malformed (the message names file, line, value),
2 bad arguments.
)";

ros::Time fromNanoseconds(std::int64_t ns) {
  ros::Time t;
  t.fromNSec(static_cast<std::uint64_t>(ns));
  return t;
}

int writeCamera(rosbag::Bag& bag, const ev::EurocSequence& seq, const std::string& camera) {
  int count = 0;
  for (const ev::FrameRef& frame : seq.frames) {
    std::string error;
    const cv::Mat image = ev::readGrayChecked(frame.path, enhanced_orb::kMaxImagePixels, error);
    if (image.empty()) {
      throw ev::DatasetError(error);
    }
    sensor_msgs::Image msg;
    msg.header.seq = static_cast<std::uint32_t>(count);
    msg.header.stamp = fromNanoseconds(frame.stamp);
    msg.header.frame_id = camera;
    msg.height = static_cast<std::uint32_t>(image.rows);
    msg.width = static_cast<std::uint32_t>(image.cols);
    msg.encoding = sensor_msgs::image_encodings::MONO8;
    msg.step = msg.width;
    msg.data.resize(static_cast<size_t>(msg.step) * msg.height);
    for (int y = 0; y < image.rows; ++y) {
      std::copy(image.ptr<std::uint8_t>(y), image.ptr<std::uint8_t>(y) + image.cols,
                msg.data.begin() + static_cast<std::ptrdiff_t>(y) * msg.step);
    }
    bag.write("/" + camera + "/image_raw", msg.header.stamp, msg);
    ++count;
  }
  if (!seq.missing.empty()) {
    std::cerr << "euroc_to_bag: warning: " << seq.missing.size() << " images listed in " << seq.mav0 << "/" << camera
              << "/data.csv are missing (first: " << seq.missing.front() << "); skipped\n";
  }
  return count;
}

int writeImu(rosbag::Bag& bag, const fs::path& mav0) {
  const std::string file = (mav0 / "imu0" / "data.csv").string();
  int count = 0;
  for (const ev::CsvRow& row : ev::readCsv(file)) {
    if (row.fields.size() < 7) {
      throw ev::DatasetError(file + ":" + std::to_string(row.line) +
                             ": expected 7 fields (timestamp, w_x, w_y, w_z, a_x, a_y, a_z)");
    }
    sensor_msgs::Imu msg;
    msg.header.seq = static_cast<std::uint32_t>(count);
    msg.header.stamp = fromNanoseconds(ev::csvInteger(file, row, 0, "timestamp"));
    msg.header.frame_id = "imu4";
    msg.angular_velocity.x = ev::csvNumber(file, row, 1, "w_x");
    msg.angular_velocity.y = ev::csvNumber(file, row, 2, "w_y");
    msg.angular_velocity.z = ev::csvNumber(file, row, 3, "w_z");
    msg.linear_acceleration.x = ev::csvNumber(file, row, 4, "a_x");
    msg.linear_acceleration.y = ev::csvNumber(file, row, 5, "a_y");
    msg.linear_acceleration.z = ev::csvNumber(file, row, 6, "a_z");
    msg.orientation_covariance[0] = -1.0;  // no orientation estimate
    bag.write("/imu0", msg.header.stamp, msg);
    ++count;
  }
  return count;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && (std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help")) {
    std::cout << kUsage;
    return 0;
  }
  if (argc != 3) {
    std::cerr << kUsage;
    return 2;
  }
  fs::path mav0 = argv[1];
  if (fs::is_directory(mav0 / "mav0")) {
    mav0 /= "mav0";
  }
  const std::string output = argv[2];
  std::vector<std::string> cameras;
  for (const char* camera : {"cam0", "cam1"}) {
    if (fs::exists(mav0 / camera / "data.csv")) {
      cameras.push_back(camera);
    }
  }
  const bool imu = fs::exists(mav0 / "imu0" / "data.csv");
  if (cameras.empty() && !imu) {
    std::cerr << "euroc_to_bag: no mav0/cam0, mav0/cam1 or mav0/imu0 with data.csv under " << argv[1] << "\n";
    return 1;
  }
  try {
    // Read every listing first: a bad one ends the run before anything is written.
    std::vector<ev::EurocSequence> sequences;
    for (const std::string& camera : cameras) {
      sequences.push_back(ev::readEuroc(mav0.string(), camera));
      for (const ev::FrameRef& frame : sequences.back().frames) {
        if (ev::sameFile(frame.path, output)) {
          std::cerr << "euroc_to_bag: the output " << output << " is an input image; refusing to overwrite it\n";
          return 2;
        }
      }
    }
    for (const char* csv : {"cam0/data.csv", "cam1/data.csv", "imu0/data.csv"}) {
      if (ev::sameFile((mav0 / csv).string(), output)) {
        std::cerr << "euroc_to_bag: the output " << output << " is the input " << (mav0 / csv).string()
                  << "; refusing to overwrite it\n";
        return 2;
      }
    }
    ev::AtomicFile file(output);
    rosbag::Bag bag(file.temporary(), rosbag::bagmode::Write);
    for (size_t i = 0; i < cameras.size(); ++i) {
      std::cout << "/" << cameras[i] << "/image_raw: " << writeCamera(bag, sequences[i], cameras[i]) << " images\n";
    }
    if (imu) {
      std::cout << "/imu0: " << writeImu(bag, mav0) << " samples\n";
    }
    bag.close();
    file.commit();
  } catch (const std::exception& e) {
    std::cerr << "euroc_to_bag: " << e.what() << "\n";
    return 1;
  }
  std::cout << "wrote " << output << "\n";
  return 0;
}
