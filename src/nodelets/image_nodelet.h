// Plumbing shared by the package's nodelets: one input image subscribed lazily, ~queue_size and
// transport hints, input checks with throttled warnings, diagnostics of rate and processing time.
#ifndef ENHANCED_ORB_IMAGE_NODELET_H
#define ENHANCED_ORB_IMAGE_NODELET_H

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <image_transport/image_transport.h>
#include <nodelet/nodelet.h>
#include <ros/ros.h>
#include <sensor_msgs/Image.h>
#include <opencv2/core.hpp>

#include "enhanced_orb/camera_motion.h"
#include "enhanced_orb/params.h"

namespace enhanced_orb {

class ImageNodelet : public nodelet::Nodelet {
protected:
  // Advertises the outputs, giving each connectCallback() (image_transport) or
  // connectCallbackRos() (plain topics) as its connect callback, and starts reconfiguration.
  // Runs with the connect mutex held, so no connect callback sees half-made publishers.
  virtual void advertiseOutputs() = 0;
  // Whether any output has a subscriber; the input is subscribed only while one has.
  virtual bool outputsHaveSubscribers() const = 0;
  // Processes one valid input; `gray` is the input as 8-bit gray (it may share `msg`'s buffer),
  // which took `convert_ms` to make. Exceptions are caught, logged and counted by the caller.
  virtual void process(const sensor_msgs::ImageConstPtr& msg, const cv::Mat& gray, double convert_ms) = 0;

  // Adds a nodelet's own values to its /diagnostics status (called once a second).
  virtual void addDiagnostics(diagnostic_updater::DiagnosticStatusWrapper& /*status*/) {}

  image_transport::SubscriberStatusCallback connectCallback();
  ros::SubscriberStatusCallback connectCallbackRos();

  // Logs `message` as a warning at most every 5 s for each `reason`; a new reason logs at once.
  void warnThrottled(const std::string& reason, const std::string& message);

  // With ~debug_addresses, publishes where an image message lives on ~debug/<topic>
  // (diagnostic_msgs/KeyValue: key = its stamp in ns, value = its address), so that a test in the
  // same process can prove that images pass between nodelets without a copy.
  void publishAddress(ros::Publisher& pub, const sensor_msgs::Image& image);
  ros::Publisher advertiseAddress(const std::string& topic);

  // After a reconfiguration to `params`: warns about each parameter in `values` (name -> value as
  // text) that changed since the last call and has no effect under `params`, naming the reason.
  void warnInactive(const Params& params, const std::map<std::string, std::string>& values);

  // Warns about each private parameter whose type on the parameter server is not the one the
  // nodelet reads (`queue_size: ten`, `c_min: "abc"`): such a value is ignored for the default.
  // `expected`: name -> "bool", "int", "double" or "str" (dynamic_reconfigure's type names).
  void warnWrongTypes(const std::map<std::string, std::string>& expected);

  // Reads ~preset, logging it (an unknown name: an error, and the default mode).
  Preset readPreset();
  // Sets the private parameter `name` from text as a value of dynamic_reconfigure's `type`.
  void setTyped(const std::string& name, const std::string& type, const std::string& text);

  // Whether the camera is judged moving at this image (camera_motion auto: `judge`), the images
  // taken in order as one stream (CameraMotion). A stamp before the last one (a bag played again)
  // starts a new stream; each change of the judgment is logged, and a new scene (throttled).
  // Not judging: still (and the stream is forgotten).
  StreamJudgment judgeMotion(const ros::Time& stamp, const cv::Mat& gray, bool judge);

  image_transport::ImageTransport& transport() { return *it_; }
  // ~queue_size: of the input subscription and of every output, so that a subscriber in another
  // process that reads in bursts loses nothing the nodelet could keep.
  uint32_t queueSize() const { return static_cast<uint32_t>(queue_size_); }

private:
  void onInit() final;
  void connect();
  void subscribeInput();  // with ~image_transport; raw when that transport cannot be loaded
  void checkStarted();
  void imageCallback(const sensor_msgs::ImageConstPtr& msg);
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  std::unique_ptr<image_transport::ImageTransport> it_;
  image_transport::Subscriber sub_;
  std::mutex connect_mutex_;
  static constexpr double kStartupCheckS = 10.0;
  ros::WallTimer startup_timer_;
  bool ever_subscribed_ = false;  // under connect_mutex_
  std::atomic<bool> ever_received_{false};
  ros::WallTime subscribed_at_;
  int queue_size_ = 5;
  bool debug_addresses_ = false;

  std::map<std::string, std::string> last_values_;

  std::mutex motion_mutex_;
  CameraMotion motion_;
  ros::Time last_stamp_;

  std::mutex log_mutex_;
  std::map<std::string, ros::WallTime> last_warning_;

  // Diagnostics over the last period.
  std::unique_ptr<diagnostic_updater::Updater> updater_;
  ros::WallTimer diagnostics_timer_;
  std::mutex stats_mutex_;
  ros::WallTime window_start_;
  int processed_ = 0;
  int rejected_ = 0;
  int failed_ = 0;
  std::uint64_t dropped_ = 0;  // header.seq gaps in this period
  std::uint64_t dropped_total_ = 0;
  std::optional<std::uint32_t> last_seq_;
  double total_ms_ = 0.0;
  double max_ms_ = 0.0;
};

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_IMAGE_NODELET_H
