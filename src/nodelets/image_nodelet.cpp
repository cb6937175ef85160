#include "image_nodelet.h"

#include <chrono>
#include <cstdint>
#include <exception>
#include <sstream>

#include <diagnostic_msgs/KeyValue.h>

#include "enhanced_orb/ros/conversions.h"

namespace enhanced_orb {

void ImageNodelet::onInit() {
  ros::NodeHandle& nh = getNodeHandle();
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  it_ = std::make_unique<image_transport::ImageTransport>(nh);
  warnWrongTypes({{"queue_size", "int"}, {"image_transport", "str"}, {"debug_addresses", "bool"}, {"preset", "str"}});
  pnh.param("queue_size", queue_size_, 5);
  if (queue_size_ < 1) {
    NODELET_WARN("~queue_size = %d is out of range [1, inf); using 1", queue_size_);
    queue_size_ = 1;
  }
  pnh.param("debug_addresses", debug_addresses_, false);

  updater_ = std::make_unique<diagnostic_updater::Updater>(nh, pnh, getName());
  updater_->setHardwareID("none");
  updater_->add("processing", this, &ImageNodelet::diagnose);
  window_start_ = ros::WallTime::now();
  diagnostics_timer_ =
      nh.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { updater_->update(); });

  startup_timer_ = nh.createWallTimer(
      ros::WallDuration(kStartupCheckS), [this](const ros::WallTimerEvent&) { checkStarted(); }, true);

  std::lock_guard<std::mutex> lock(connect_mutex_);
  advertiseOutputs();
}

image_transport::SubscriberStatusCallback ImageNodelet::connectCallback() {
  return [this](const image_transport::SingleSubscriberPublisher&) { connect(); };
}

ros::SubscriberStatusCallback ImageNodelet::connectCallbackRos() {
  return [this](const ros::SingleSubscriberPublisher&) { connect(); };
}

void ImageNodelet::connect() {
  try {
    std::lock_guard<std::mutex> lock(connect_mutex_);
    const bool wanted = outputsHaveSubscribers();
    if (wanted) {
      ever_subscribed_ = true;
    }
    if (wanted && !sub_) {
      subscribeInput();
    } else if (!wanted && sub_) {
      NODELET_DEBUG("no subscriber left: unsubscribing %s", sub_.getTopic().c_str());
      sub_.shutdown();
    }
  } catch (const std::exception& e) {
    NODELET_ERROR("cannot (un)subscribe the input: %s", e.what());
  }
}

void ImageNodelet::subscribeInput() {
  const image_transport::TransportHints hints("raw", ros::TransportHints(), getPrivateNodeHandle());
  try {
    sub_ = it_->subscribe("image", queueSize(), &ImageNodelet::imageCallback, this, hints);
  } catch (const image_transport::TransportLoadException& e) {
    // A transport whose plugin is not installed: say which ones are, and read raw images instead.
    std::string available;
    for (const std::string& name : it_->getLoadableTransports()) {
      available += (available.empty() ? "" : ", ") + name;
    }
    NODELET_ERROR("image_transport '%s' cannot be loaded (%s); loadable here: %s; subscribing raw images instead",
                  hints.getTransport().c_str(), e.what(), available.c_str());
    sub_ = it_->subscribe("image", queueSize(), &ImageNodelet::imageCallback, this,
                          image_transport::TransportHints("raw"));
  }
  subscribed_at_ = ros::WallTime::now();
  NODELET_DEBUG("subscribed to %s (%s)", sub_.getTopic().c_str(), sub_.getTransport().c_str());
}

void ImageNodelet::checkStarted() {
  // One-shot warnings, as opencv_apps gives: a chain nobody listens to, or an input that never comes.
  std::lock_guard<std::mutex> lock(connect_mutex_);
  if (!ever_subscribed_) {
    NODELET_WARN("no subscriber on any output after %.0f s: the input is subscribed only while an output has one",
                 kStartupCheckS);
  } else if (sub_ && !ever_received_ && (ros::WallTime::now() - subscribed_at_).toSec() >= kStartupCheckS) {
    NODELET_WARN("no image arrived on %s in %.0f s (publisher %s)", sub_.getTopic().c_str(), kStartupCheckS,
                 sub_.getNumPublishers() ? "connected" : "missing");
  }
}

void ImageNodelet::imageCallback(const sensor_msgs::ImageConstPtr& msg) {
  ever_received_ = true;
  {
    // Frames lost before this callback (a full input queue, a slow link) show as gaps in
    // header.seq, where the publisher numbers its messages (drivers and rosbag do).
    std::lock_guard<std::mutex> lock(stats_mutex_);
    const std::uint32_t seq = msg->header.seq;
    if (last_seq_ && seq > *last_seq_ + 1) {
      dropped_ += seq - *last_seq_ - 1;
      dropped_total_ += seq - *last_seq_ - 1;
    }
    last_seq_ = seq;
  }
  const auto converting = std::chrono::steady_clock::now();
  const GrayImage input = toGrayImage(msg);
  const double convert_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - converting).count();
  if (!input.error.empty()) {
    warnThrottled(input.reason, input.error);
    std::lock_guard<std::mutex> lock(stats_mutex_);
    ++rejected_;
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  bool ok = false;
  try {
    process(msg, input.gray, convert_ms);
    ok = true;
  } catch (const std::exception& e) {
    warnThrottled("exception", std::string("processing failed, image dropped: ") + e.what());
  } catch (...) {
    warnThrottled("exception", "processing failed with an unknown exception, image dropped");
  }
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::lock_guard<std::mutex> lock(stats_mutex_);
  if (ok) {
    ++processed_;
    total_ms_ += ms;
    max_ms_ = std::max(max_ms_, ms);
  } else {
    ++failed_;
  }
}

void ImageNodelet::warnThrottled(const std::string& reason, const std::string& message) {
  const ros::WallTime now = ros::WallTime::now();
  {
    std::lock_guard<std::mutex> lock(log_mutex_);
    auto it = last_warning_.find(reason);
    if (it != last_warning_.end() && (now - it->second).toSec() < 5.0) {
      return;
    }
    last_warning_[reason] = now;
  }
  NODELET_WARN("%s", message.c_str());
}

ros::Publisher ImageNodelet::advertiseAddress(const std::string& topic) {
  return debug_addresses_ ? getPrivateNodeHandle().advertise<diagnostic_msgs::KeyValue>("debug/" + topic, 100)
                          : ros::Publisher();
}

void ImageNodelet::publishAddress(ros::Publisher& pub, const sensor_msgs::Image& image) {
  if (pub) {
    diagnostic_msgs::KeyValue msg;
    msg.key = std::to_string(image.header.stamp.toNSec());
    msg.value = std::to_string(reinterpret_cast<std::uintptr_t>(&image));
    pub.publish(msg);
  }
}

void ImageNodelet::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status) {
  bool subscribed = false;
  {
    std::lock_guard<std::mutex> lock(connect_mutex_);
    subscribed = static_cast<bool>(sub_);
  }
  std::lock_guard<std::mutex> lock(stats_mutex_);
  const ros::WallTime now = ros::WallTime::now();
  const double seconds = std::max(1e-6, (now - window_start_).toSec());
  status.add("frames per second", processed_ / seconds);
  status.add("mean processing time [ms]", processed_ ? total_ms_ / processed_ : 0.0);
  status.add("max processing time [ms]", max_ms_);
  status.add("frames rejected (bad input)", rejected_);
  status.add("frames failed", failed_);
  status.add("input frames missed (header.seq gaps)", dropped_);
  status.add("input frames missed since start", dropped_total_);
  status.add("input subscribed", subscribed);
  addDiagnostics(status);
  if (failed_ > 0) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "processing failed on some frames");
  } else if (rejected_ > 0) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "some input frames were rejected");
  } else if (dropped_ > 0) {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "input frames were missed (queue full or link slow)");
  } else if (!subscribed) {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "idle: no subscriber on the outputs");
  } else {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "ok");
  }
  window_start_ = now;
  processed_ = rejected_ = failed_ = 0;
  dropped_ = 0;
  total_ms_ = max_ms_ = 0.0;
}

StreamJudgment ImageNodelet::judgeMotion(const ros::Time& stamp, const cv::Mat& gray, bool judge) {
  std::lock_guard<std::mutex> lock(motion_mutex_);
  if (!judge) {
    motion_.reset();
    return {};
  }
  if (stamp < last_stamp_) {
    NODELET_INFO("image stamps went back (%.3f s after %.3f s): the camera's motion is judged anew", stamp.toSec(),
                 last_stamp_.toSec());
    motion_.reset();
  }
  last_stamp_ = stamp;
  const bool was_moving = motion_.moving();
  const StreamJudgment judged = motion_.judge(gray);
  const bool moving = judged.moving;
  if (motion_.newScene()) {
    NODELET_INFO_THROTTLE(5.0,
                          "image unrelated to the last one (a new scene, or another camera): its shift is "
                          "measured anew, and the camera stays judged %s",
                          moving ? "moving" : "still");
  }
  if (moving != was_moving) {
    NODELET_INFO("camera judged %s (shift %.1f px): the %s camera's settings from now on", moving ? "moving" : "still",
                 motion_.shift(), moving ? "moving" : "still");
  }
  return judged;
}

void ImageNodelet::warnInactive(const Params& params, const std::map<std::string, std::string>& values) {
  const bool first = last_values_.empty();
  for (const std::string& inactive : inactiveParameters(params)) {
    const std::string name = inactive.substr(0, inactive.find(':'));
    const auto value = values.find(name);
    if (value == values.end()) {
      continue;
    }
    const auto last = last_values_.find(name);
    if (!first && (last == last_values_.end() || last->second != value->second)) {
      NODELET_WARN("%s = %s has no effect now (%s)", name.c_str(), value->second.c_str(),
                   inactive.substr(inactive.find(':') + 2).c_str());
    }
  }
  last_values_ = values;
}

void ImageNodelet::warnWrongTypes(const std::map<std::string, std::string>& expected) {
  using XmlRpc::XmlRpcValue;
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  for (const auto& [name, type] : expected) {
    XmlRpcValue value;
    if (!pnh.getParam(name, value)) {
      continue;
    }
    const XmlRpcValue::Type got = value.getType();
    const bool ok = type == "bool"     ? got == XmlRpcValue::TypeBoolean
                    : type == "int"    ? got == XmlRpcValue::TypeInt
                    : type == "double" ? got == XmlRpcValue::TypeDouble || got == XmlRpcValue::TypeInt
                                       : got == XmlRpcValue::TypeString;
    if (ok) {
      continue;
    }
    std::string text = "a value of another type";
    if (got == XmlRpcValue::TypeString) {
      text = "'" + static_cast<std::string&>(value) + "'";
    } else if (got == XmlRpcValue::TypeInt) {
      text = std::to_string(static_cast<int>(value));
    } else if (got == XmlRpcValue::TypeDouble) {
      text = std::to_string(static_cast<double>(value));
    } else if (got == XmlRpcValue::TypeBoolean) {
      text = static_cast<bool>(value) ? "true" : "false";
    }
    const char* wanted = type == "bool"     ? "a bool"
                         : type == "int"    ? "an int"
                         : type == "double" ? "a number"
                                            : "a string";
    NODELET_WARN("~%s = %s is not %s; it is ignored and the default is used", name.c_str(), text.c_str(), wanted);
  }
}

Preset ImageNodelet::readPreset() {
  const std::string name = getPrivateNodeHandle().param<std::string>("preset", "default");
  Preset preset = Preset::kDefault;
  if (!parsePreset(name, preset)) {
    NODELET_ERROR("preset '%s' is not %s; using default", name.c_str(), presetNames().c_str());
  }
  NODELET_INFO("preset %s", toString(preset));
  return preset;
}

void ImageNodelet::setTyped(const std::string& name, const std::string& type, const std::string& text) {
  ros::NodeHandle& pnh = getPrivateNodeHandle();
  if (type == "int") {
    pnh.setParam(name, std::stoi(text));
  } else if (type == "double") {
    pnh.setParam(name, std::stod(text));
  } else if (type == "bool") {
    pnh.setParam(name, text == "true");
  } else {
    pnh.setParam(name, text);
  }
}

}  // namespace enhanced_orb
