// Loads EnhanceNodelet and ExtractNodelet into this process with nodelet::Loader, feeds frames and
// checks that the image the extractor receives is the very object the enhancer published.
#include <algorithm>
#include <map>
#include <mutex>
#include <set>
#include <sstream>
#include <string>

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

  // The spinner's threads run this fixture's callbacks, which write its maps: they are joined, and
  // the subscriptions closed, before any member is destroyed (a message still arriving from the
  // chain would otherwise be recorded into a map already gone).
  void TearDown() override {
    spinner_.stop();
    for (ros::Subscriber* sub : {&published_sub_, &received_sub_, &probe_sub_, &keypoints_sub_}) {
      sub->shutdown();
    }
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
  void onKeypoints(const enhanced_orb::KeypointArrayConstPtr& m) {
    std::lock_guard<std::mutex> lock(mutex_);
    keypoints_.insert(m->header.stamp.toNSec());
  }

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
  std::set<std::uint64_t> keypoints_;  // stamps whose keypoints arrived
};

// Each frame is sent once the last one has come through entirely (its keypoints and its three
// addresses), so that no queue can drop one whatever the machine's load; each wait is bounded
// generously (kFrameSeconds) and a failure says which of a frame's messages did not arrive.
constexpr double kFrameSeconds = 30.0;

TEST_F(ZeroCopy, ExtractorReceivesTheEnhancersMessageItself) {
  // The subscription on keypoints makes the chain subscribe its inputs (lazily).
  ASSERT_TRUE(waitFor([&] { return image_pub_.getNumSubscribers() > 0; }, kFrameSeconds))
      << "enhancer never subscribed";
  auto stamp = [](int i) { return ros::Time(1000 + i).toNSec(); };
  // What of frame i has not arrived: "" once everything has.
  auto missing = [&](int i) {
    std::lock_guard<std::mutex> lock(mutex_);
    std::string what;
    for (const auto& [name, seen] : {std::make_pair("its keypoints", keypoints_.count(stamp(i)) > 0),
                                     std::make_pair("the enhancer's output address", published_.count(stamp(i)) > 0),
                                     std::make_pair("the extractor's input address", received_.count(stamp(i)) > 0),
                                     std::make_pair("this process's probe", probed_.count(stamp(i)) > 0)}) {
      if (!seen) {
        what += what.empty() ? name : std::string(", ") + name;
      }
    }
    return what;
  };
  // The enhancer may subscribe (for this test's probe) before the extractor does, and this test's
  // subscriptions to the debug topics connect in their own time: warm the chain up until a frame
  // has come through entirely. A warm-up frame sent before everything connected may be lost on the
  // way; the next one is sent once it is clear that this one will not come through.
  bool warm = false;
  for (int i = 0; i < 20 && !warm; ++i) {
    image_pub_.publish(frame(100 + i));
    warm = waitFor([&] { return missing(100 + i).empty(); }, 2.0);
  }
  ASSERT_TRUE(warm) << "no frame came through the chain with its keypoints and addresses";
  // A late warm-up frame's messages are left to arrive before the measured frames are sent.
  ros::WallDuration(0.5).sleep();
  const int frames = 10;
  for (int i = 0; i < frames; ++i) {
    image_pub_.publish(frame(i));
    ASSERT_TRUE(waitFor([&] { return missing(i).empty(); }, kFrameSeconds))
        << "frame " << i << " sent to a connected, idle chain: after " << kFrameSeconds << " s still missing "
        << missing(i);
  }
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
