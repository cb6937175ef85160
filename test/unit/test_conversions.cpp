#include <gtest/gtest.h>
#include <boost/make_shared.hpp>

#include "enhanced_orb/ros/conversions.h"

using namespace enhanced_orb;

namespace {

sensor_msgs::ImagePtr message(const std::string& encoding, int width, int height, int bytes_per_pixel) {
  auto msg = boost::make_shared<sensor_msgs::Image>();
  msg->encoding = encoding;
  msg->width = width;
  msg->height = height;
  msg->step = width * bytes_per_pixel;
  msg->data.assign(static_cast<size_t>(msg->step) * height, 0);
  for (size_t i = 0; i < msg->data.size(); ++i) {
    msg->data[i] = static_cast<uint8_t>(i * 7);
  }
  return msg;
}

}  // namespace

TEST(ToGrayImage, Mono8SharesTheMessageBuffer) {
  const auto msg = message("mono8", 8, 4, 1);
  const GrayImage g = toGrayImage(msg);
  ASSERT_TRUE(g.error.empty()) << g.error;
  EXPECT_EQ(g.gray.data, msg->data.data());
  EXPECT_EQ(g.gray.size(), cv::Size(8, 4));
}

TEST(ToGrayImage, PaddedRowsUseTheStep) {
  auto msg = message("mono8", 5, 3, 1);
  msg->step = 8;
  msg->data.assign(24, 9);
  msg->data[8 + 4] = 200;  // row 1, column 4
  const GrayImage g = toGrayImage(msg);
  ASSERT_TRUE(g.error.empty()) << g.error;
  EXPECT_EQ(g.gray.at<uint8_t>(1, 4), 200);
}

TEST(ToGrayImage, Mono16BothEndiannesses) {
  auto msg = message("mono16", 2, 1, 2);
  msg->data = {0x0A, 0x0A, 0xFF, 0xFF};  // little endian: 2570 = 257 * 10, 65535
  GrayImage g = toGrayImage(msg);
  ASSERT_TRUE(g.error.empty()) << g.error;
  EXPECT_EQ(g.gray.at<uint8_t>(0, 0), 10);
  EXPECT_EQ(g.gray.at<uint8_t>(0, 1), 255);
  msg->is_bigendian = 1;
  msg->data = {0x00, 0xFF, 0x01, 0x01};  // big endian: 255 -> 1, 257 -> 1
  g = toGrayImage(msg);
  ASSERT_TRUE(g.error.empty()) << g.error;
  EXPECT_EQ(g.gray.at<uint8_t>(0, 0), 1);
  EXPECT_EQ(g.gray.at<uint8_t>(0, 1), 1);
}

TEST(ToGrayImage, EveryListedEncodingConverts) {
  const std::vector<std::pair<std::string, int>> encodings = {
      {"mono8", 1},       {"8UC1", 1},        {"mono16", 2}, {"16UC1", 2},       {"bgr8", 3},
      {"rgb8", 3},        {"bgra8", 4},       {"rgba8", 4},  {"bayer_rggb8", 1}, {"bayer_bggr8", 1},
      {"bayer_gbrg8", 1}, {"bayer_grbg8", 1}, {"yuv422", 2}};
  for (const auto& [encoding, bytes] : encodings) {
    EXPECT_TRUE(isSupportedEncoding(encoding));
    const GrayImage g = toGrayImage(message(encoding, 16, 8, bytes));
    EXPECT_TRUE(g.error.empty()) << encoding << ": " << g.error;
    EXPECT_EQ(g.gray.type(), CV_8UC1) << encoding;
    EXPECT_EQ(g.gray.size(), cv::Size(16, 8)) << encoding;
  }
}

TEST(ToGrayImage, BadMessagesAreRejectedWithAReason) {
  struct Case {
    sensor_msgs::ImagePtr msg;
    std::string reason;
    std::string text;
  };
  auto short_data = message("mono8", 16, 8, 1);
  short_data->data.resize(100);
  auto small_step = message("bgr8", 16, 8, 3);
  small_step->step = 47;
  auto huge = message("mono8", 1, 1, 1);
  huge->width = 8000;
  huge->height = 8000;
  const std::vector<Case> cases = {
      {message("32FC1", 4, 4, 4), "encoding:32FC1", "unsupported encoding '32FC1'"},
      {message("8UC3", 4, 4, 3), "encoding:8UC3", "unsupported encoding '8UC3'"},
      {message("mono8", 0, 0, 1), "empty", "empty 0x0"},
      {short_data, "data", "data holds 100 bytes, step x height needs 128"},
      {small_step, "step", "step 47 is smaller than a bgr8 row"},
      {huge, "huge", "8000x8000 image dropped"},
  };
  for (const Case& c : cases) {
    const GrayImage g = toGrayImage(c.msg);
    EXPECT_TRUE(g.gray.empty());
    EXPECT_EQ(g.reason, c.reason);
    EXPECT_NE(g.error.find(c.text), std::string::npos) << "'" << g.error << "' lacks '" << c.text << "'";
  }
}

TEST(ToMessage, CarriesEveryField) {
  Extraction e;
  e.image = cv::Mat(48, 64, CV_8UC1);
  e.keypoints = {cv::KeyPoint(10.5f, 20.25f, 37.2f, 123.0f, 42.0f, 1), cv::KeyPoint(1, 2, 31, 0, 7, 0)};
  e.descriptors = cv::Mat(2, kDescriptorBytes, CV_8U);
  cv::randu(e.descriptors, 0, 256);
  e.cell_thresholds = (cv::Mat_<int>(2, 2) << 7, 8, 9, 10);
  e.level_thresholds = {e.cell_thresholds, e.cell_thresholds, e.cell_thresholds};
  e.timings.extract_ms = 2.5;
  e.timings.convert_ms = 0.25;
  e.timings.judge_ms = 0.5;
  e.timings.enhance_ms = 1.0;
  std_msgs::Header header;
  header.stamp = ros::Time(5, 6);
  header.frame_id = "cam0";
  const KeypointArrayPtr m = toMessage(e, header, Params());
  EXPECT_EQ(m->header.stamp, header.stamp);
  EXPECT_EQ(m->header.frame_id, "cam0");
  EXPECT_EQ(m->width, 64u);
  EXPECT_EQ(m->height, 48u);
  ASSERT_EQ(m->keypoints.size(), 2u);
  EXPECT_FLOAT_EQ(m->keypoints[0].x, 10.5f);
  EXPECT_FLOAT_EQ(m->keypoints[0].y, 20.25f);
  EXPECT_FLOAT_EQ(m->keypoints[0].size, 37.2f);
  EXPECT_FLOAT_EQ(m->keypoints[0].angle, 123.0f);
  EXPECT_FLOAT_EQ(m->keypoints[0].response, 42.0f);
  EXPECT_EQ(m->keypoints[0].octave, 1);
  EXPECT_EQ(m->descriptor_bytes, 32u);
  ASSERT_EQ(m->descriptors.size(), 64u);
  EXPECT_EQ(m->descriptors[33], e.descriptors.at<uint8_t>(1, 1));
  EXPECT_EQ(m->grid_size, 2u);
  EXPECT_EQ(m->cell_thresholds, (std::vector<int32_t>{7, 8, 9, 10}));
  EXPECT_EQ(m->threshold_mode, "adaptive");
  EXPECT_EQ(m->n_levels, 3u);
  EXPECT_FLOAT_EQ(m->scale_factor, 1.2f);
  EXPECT_FLOAT_EQ(m->extract_ms, 2.5f);
  EXPECT_FLOAT_EQ(m->judge_ms, 0.5f);
  EXPECT_FLOAT_EQ(m->total_ms, 4.25f);  // conversion, judgment, enhancement and extraction
}
