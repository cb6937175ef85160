// Loads EnhanceNodelet and ExtractNodelet into this process with nodelet::Loader, feeds frames and
// checks that the image the extractor receives is the very object the enhancer published.
#include <algorithm>
#include <atomic>
#include <map>
#include <mutex>
#include <set>

#include <diagnostic_msgs/KeyValue.h>
#include <gtest/gtest.h>
#include <nodelet/loader.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <boost/make_shared.hpp>
#include <opencv2/imgcodecs.hpp>

#include "enhanced_orb/KeypointArray.h"

namespace {

class ZeroCopy : public ::testing::Test {
protected:
  void SetUp() override {
    ros::param::set("/zc/enhance/debug_addresses", true);
    ros::param::set("/zc/extract/debug_addresses", true);
    nodelet::M_string enhance_remap{{"/zc/image", "/zc/image_raw"}};
    nodelet::M_string extract_remap{{"/zc/image", "/zc/image_enhanced"}};
    const nodelet::V_string no_args;
    ASSERT_TRUE(loader_.load("/zc/enhance", "enhanced_orb/EnhanceNodelet", enhance_remap, no_args));
    ASSERT_TRUE(loader_.load("/zc/extract", "enhanced_orb/ExtractNodelet", extract_remap, no_args));

    ros::NodeHandle nh;
    published_sub_ = nh.subscribe("/zc/enhance/debug/output_address", 100, &ZeroCopy::onPublished, this);
    received_sub_ = nh.subscribe("/zc/extract/debug/input_address", 100, &ZeroCopy::onReceived, this);
    probe_sub_ = nh.subscribe("/zc/image_enhanced", 100, &ZeroCopy::onProbe, this);
    keypoints_sub_ = nh.subscribe("/zc/keypoints", 100, &ZeroCopy::onKeypoints, this);
    image_pub_ = nh.advertise<sensor_msgs::Image>("/zc/image_raw", 10);
    spinner_.start();
  }

  // Addresses by image stamp [ns]: as the enhancer published, as the extractor received, and as
  // this process's own subscriber received. A stamp can be published more than once (an input
  // frame delivered to the enhancer twice), so each stamp keeps every address it was seen at.
  using Addresses = std::map<std::uint64_t, std::set<std::uint64_t>>;
  void onPublished(const diagnostic_msgs::KeyValueConstPtr& m) { record(published_, m->key, m->value); }
  void onReceived(const diagnostic_msgs::KeyValueConstPtr& m) { record(received_, m->key, m->value); }
  void onProbe(const sensor_msgs::ImageConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    probed_[m->header.stamp.toNSec()].insert(reinterpret_cast<std::uint64_t>(m.get()));
  }
  void onKeypoints(const enhanced_orb::KeypointArrayConstPtr&) { ++keypoints_; }

  void record(Addresses& addresses, const std::string& stamp, const std::string& address) {
    std::lock_guard<std::mutex> lock(mutex_);
    addresses[std::stoull(stamp)].insert(std::stoull(address));
  }

  // Waits until `condition` holds, up to `seconds`.
  template <typename F>
  bool waitFor(F condition, double seconds) {
    const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(seconds);
    while (ros::ok() && ros::WallTime::now() < deadline) {
      if (condition()) {
        return true;
      }
      ros::WallDuration(0.01).sleep();
    }
    return false;
  }

  static sensor_msgs::ImagePtr frame(int index) {
    cv::Mat gray = cv::imread(ENHANCED_ORB_EUROC_DIR "/mav0/cam0/data/1403715273262142976.png", cv::IMREAD_GRAYSCALE);
    if (gray.empty()) {
      gray = cv::Mat(480, 752, CV_8UC1);
      cv::randu(gray, 0, 256);
    }
    auto msg = boost::make_shared<sensor_msgs::Image>();
    msg->header.stamp = ros::Time(1000 + index);
    msg->header.frame_id = "cam0";
    msg->height = gray.rows;
    msg->width = gray.cols;
    msg->encoding = "mono8";
    msg->step = gray.cols;
    msg->data.assign(gray.datastart, gray.dataend);
    return msg;
  }

  nodelet::Loader loader_{false};
  ros::AsyncSpinner spinner_{2};
  ros::Subscriber published_sub_, received_sub_, probe_sub_, keypoints_sub_;
  ros::Publisher image_pub_;
  std::mutex mutex_;
  Addresses published_, received_, probed_;
  std::atomic<int> keypoints_{0};
};

TEST_F(ZeroCopy, ExtractorReceivesTheEnhancersMessageItself) {
  // The subscription on keypoints makes the chain subscribe its inputs (lazily).
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() > 0; }, 20.0)) << "enhancer never subscribed";
  // The enhancer may subscribe (for this test's probe) before the extractor does, and this test's
  // subscriptions to the debug topics connect in their own time: warm the chain up until a frame
  // has come through with all three of its addresses.
  auto stamp = [](int i) { return ros::Time(1000 + i).toNSec(); };
  auto seenEverywhere = [&](int i) {
    std::lock_guard<std::mutex> lock(mutex_);
    return received_.count(stamp(i)) && published_.count(stamp(i)) && probed_.count(stamp(i));
  };
  bool warm = false;
  for (int i = 0; i < 20 && !warm; ++i) {
    image_pub_.publish(frame(100 + i));
    warm = waitFor([&] { return seenEverywhere(100 + i); }, 2.0);
  }
  ASSERT_TRUE(warm) << "no frame came through the chain with its addresses";
  const int frames = 10;
  for (int i = 0; i < frames; ++i) {
    const int before = keypoints_;
    image_pub_.publish(frame(i));
    ASSERT_TRUE(waitFor([&] { return keypoints_ > before; }, 10.0)) << "no keypoints for frame " << i;
  }
  ASSERT_TRUE(waitFor(
      [&] {
        for (int i = 0; i < frames; ++i) {
          if (!seenEverywhere(i)) {
            return false;
          }
        }
        return true;
      },
      10.0))
      << "some frame's addresses never arrived";
  std::lock_guard<std::mutex> lock(mutex_);
  // Every object the extractor (or this process's subscriber) received is one the enhancer
  // published: a copy would live elsewhere.
  auto subset = [](const std::set<std::uint64_t>& seen, const std::set<std::uint64_t>& published) {
    return std::includes(published.begin(), published.end(), seen.begin(), seen.end());
  };
  for (int i = 0; i < frames; ++i) {
    const std::set<std::uint64_t>& published = published_[stamp(i)];
    EXPECT_EQ(published.count(0u), 0u);
    EXPECT_TRUE(subset(received_[stamp(i)], published)) << "frame " << i << ": the extractor got a copy";
    EXPECT_TRUE(subset(probed_[stamp(i)], published)) << "frame " << i << ": an in-process subscriber got a copy";
  }
}

}  // namespace

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "test_zero_copy");
  ros::NodeHandle keep_alive;
  return RUN_ALL_TESTS();
}
