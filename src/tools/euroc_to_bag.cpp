// euroc_to_bag: turns a EuRoC MAV dataset folder in ASL layout into a rosbag with the topics,
// types, frame ids and timestamps of EuRoC's own bags:
//   /cam0/image_raw, /cam1/image_raw  sensor_msgs/Image, mono8, frame_id cam0 / cam1
//   /imu0                             sensor_msgs/Imu, frame_id imu4
#include <cstdint>
#include <exception>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <ros/time.h>
#include <rosbag/bag.h>
#include <sensor_msgs/Image.h>
#include <sensor_msgs/Imu.h>
#include <sensor_msgs/image_encodings.h>
#include <opencv2/imgcodecs.hpp>

namespace fs = std::filesystem;

namespace {

const char* const kUsage = R"(usage: euroc_to_bag ASL_DIR OUTPUT.bag

ASL_DIR is a EuRoC sequence folder (the one holding mav0/, or mav0/ itself) with mav0/cam0,
mav0/cam1 and mav0/imu0 (each optional, at least one present). Writes /cam0/image_raw,
/cam1/image_raw (sensor_msgs/Image mono8) and /imu0 (sensor_msgs/Imu) with the dataset's stamps.
)";

ros::Time fromNanoseconds(std::uint64_t ns) {
  ros::Time t;
  t.fromNSec(ns);
  return t;
}

// Rows of a EuRoC CSV file: comma-separated fields, '#' lines skipped.
std::vector<std::vector<std::string>> readCsv(const fs::path& file) {
  std::ifstream in(file);
  if (!in) {
    throw std::runtime_error("cannot read " + file.string());
  }
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') {
      line.pop_back();
    }
    if (line.empty() || line[0] == '#') {
      continue;
    }
    std::vector<std::string> fields;
    std::istringstream fields_in(line);
    std::string field;
    while (std::getline(fields_in, field, ',')) {
      fields.push_back(field);
    }
    rows.push_back(fields);
  }
  return rows;
}

int writeCamera(rosbag::Bag& bag, const fs::path& mav0, const std::string& camera) {
  const fs::path dir = mav0 / camera;
  int count = 0;
  int missing = 0;
  for (const auto& row : readCsv(dir / "data.csv")) {
    if (row.size() < 2) {
      throw std::runtime_error("malformed line in " + (dir / "data.csv").string());
    }
    const fs::path file = dir / "data" / row[1];
    if (!fs::exists(file)) {  // excerpts list frames they do not ship
      ++missing;
      continue;
    }
    const cv::Mat image = cv::imread(file.string(), cv::IMREAD_GRAYSCALE);
    if (image.empty()) {
      throw std::runtime_error("cannot read image " + file.string());
    }
    sensor_msgs::Image msg;
    msg.header.seq = static_cast<std::uint32_t>(count);
    msg.header.stamp = fromNanoseconds(std::stoull(row[0]));
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
  if (missing > 0) {
    std::cerr << "euroc_to_bag: warning: " << missing << " images listed in " << (dir / "data.csv").string()
              << " are missing; skipped\n";
  }
  return count;
}

int writeImu(rosbag::Bag& bag, const fs::path& mav0) {
  int count = 0;
  for (const auto& row : readCsv(mav0 / "imu0" / "data.csv")) {
    if (row.size() < 7) {
      throw std::runtime_error("malformed line in imu0/data.csv");
    }
    sensor_msgs::Imu msg;
    msg.header.seq = static_cast<std::uint32_t>(count);
    msg.header.stamp = fromNanoseconds(std::stoull(row[0]));
    msg.header.frame_id = "imu4";
    msg.angular_velocity.x = std::stod(row[1]);
    msg.angular_velocity.y = std::stod(row[2]);
    msg.angular_velocity.z = std::stod(row[3]);
    msg.linear_acceleration.x = std::stod(row[4]);
    msg.linear_acceleration.y = std::stod(row[5]);
    msg.linear_acceleration.z = std::stod(row[6]);
    msg.orientation_covariance[0] = -1.0;  // no orientation estimate
    bag.write("/imu0", msg.header.stamp, msg);
    ++count;
  }
  return count;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3 || std::string(argv[1]) == "-h" || std::string(argv[1]) == "--help") {
    std::cerr << kUsage;
    return argc == 2 ? 0 : 2;
  }
  fs::path mav0 = argv[1];
  if (fs::is_directory(mav0 / "mav0")) {
    mav0 /= "mav0";
  }
  const bool cam0 = fs::exists(mav0 / "cam0" / "data.csv");
  const bool cam1 = fs::exists(mav0 / "cam1" / "data.csv");
  const bool imu = fs::exists(mav0 / "imu0" / "data.csv");
  if (!cam0 && !cam1 && !imu) {
    std::cerr << "euroc_to_bag: no mav0/cam0, mav0/cam1 or mav0/imu0 with data.csv under " << argv[1] << "\n";
    return 1;
  }
  try {
    rosbag::Bag bag(argv[2], rosbag::bagmode::Write);
    for (const auto& [present, camera] : {std::pair{cam0, "cam0"}, std::pair{cam1, "cam1"}}) {
      if (present) {
        std::cout << "/" << camera << "/image_raw: " << writeCamera(bag, mav0, camera) << " images\n";
      }
    }
    if (imu) {
      std::cout << "/imu0: " << writeImu(bag, mav0) << " samples\n";
    }
    bag.close();
  } catch (const std::exception& e) {
    std::cerr << "euroc_to_bag: " << e.what() << "\n";
    return 1;
  }
  std::cout << "wrote " << argv[2] << "\n";
  return 0;
}
