// enhanced_orb/ExtractNodelet: image -> keypoints (KeypointArray) and image_annotated (bgr8),
// ORB with the truncated adaptive threshold (section III-B) or the original fixed threshold.
#include <chrono>
#include <iomanip>
#include <memory>
#include <mutex>
#include <sstream>

#include <message_filters/cache.h>
#include <message_filters/subscriber.h>
#include <sensor_msgs/image_encodings.h>
#include <boost/make_shared.hpp>
#include <pluginlib/class_list_macros.hpp>

#include "enhanced_orb/EnhanceStatus.h"
#include "enhanced_orb/ExtractConfig.h"
#include "enhanced_orb/draw.h"
#include "enhanced_orb/orb_extractor.h"
#include "enhanced_orb/ros/conversions.h"
#include "reconfigurable_nodelet.h"

namespace enhanced_orb {

class ExtractNodelet : public ReconfigurableNodelet<ExtractConfig> {
private:
  void advertiseOutputs() override {
    startReconfigure();
    ros::NodeHandle& nh = getNodeHandle();
    keypoints_pub_ = nh.advertise<KeypointArray>("keypoints", queueSize(), connectCallbackRos(), connectCallbackRos());
    annotated_pub_ = transport().advertise("image_annotated", queueSize(), connectCallback(), connectCallback());
    address_pub_ = advertiseAddress("input_address");
    // The enhancement's statuses, kept by stamp (message_filters::Cache) for the caption of the
    // image with the same stamp; an image without one is drawn without it.
    status_sub_.subscribe(nh, "enhance_status", 10);
    statuses_.connectInput(status_sub_);
  }

  bool outputsHaveSubscribers() const override {
    return keypoints_pub_.getNumSubscribers() > 0 || annotated_pub_.getNumSubscribers() > 0;
  }

  const Fields& configFields() const override { return extractConfigFields(); }

  // The input is enhanced upstream (EnhanceNodelet) or raw on purpose (baseline).
  Params baseParams() const override { return withoutEnhancement(); }

  static Params withoutEnhancement() {
    Params p;
    p.enhance_enabled = false;
    return p;
  }

  void apply(const ExtractConfig& config, const Params& params) override {
    auto extractor = std::make_shared<const OrbExtractor>(params);  // throws std::invalid_argument
    std::lock_guard<std::mutex> lock(params_mutex_);
    extractor_ = extractor;
    draw_ = DrawOptions{config.draw_keypoints, config.draw_orientation, config.draw_grid, config.draw_text,
                        config.draw_max};
  }

  void process(const sensor_msgs::ImageConstPtr& msg, const cv::Mat& gray, double convert_ms) override {
    publishAddress(address_pub_, *msg);
    std::shared_ptr<const OrbExtractor> extractor;
    DrawOptions draw;
    {
      std::lock_guard<std::mutex> lock(params_mutex_);
      extractor = extractor_;
      draw = draw_;
    }
    ExtractOptions options;
    const auto judging = std::chrono::steady_clock::now();
    const StreamJudgment stream = judgeMotion(msg->header.stamp, gray, extractor->judgesMotion());
    options.camera_moving = stream.moving;
    options.stream_lambda = stream.stream_lambda;
    const double judge_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - judging).count();
    Extraction result;
    extractor->extract(gray, options, result);
    result.timings.convert_ms = convert_ms;
    result.timings.judge_ms = judge_ms;
    if (keypoints_pub_.getNumSubscribers() > 0) {
      keypoints_pub_.publish(toMessage(result, msg->header, extractor->params()));
    }
    if (annotated_pub_.getNumSubscribers() > 0) {
      auto out = boost::make_shared<sensor_msgs::Image>();
      out->header = msg->header;
      out->encoding = sensor_msgs::image_encodings::BGR8;
      out->height = static_cast<uint32_t>(gray.rows);
      out->width = static_cast<uint32_t>(gray.cols);
      out->step = out->width * 3;
      out->data.resize(static_cast<size_t>(out->step) * out->height);
      std::ostringstream caption;
      caption << result.keypoints.size() << " keypoints";
      if (draw.keypoints && draw.max_drawn > 0 && static_cast<int>(result.keypoints.size()) > draw.max_drawn) {
        caption << " (" << draw.max_drawn << " drawn)";
      }
      caption << std::fixed << std::setprecision(2);
      const EnhanceStatus::ConstPtr status = statusOf(msg->header.stamp);
      if (status) {
        caption << " | lambda " << status->lambda << " | tone curve " << (status->poor_quality ? "on" : "off")
                << (status->inverted ? " (inverted)" : "") << " | " << std::setprecision(1) << status->enhance_ms
                << " + ";
      } else {
        caption << " | " << std::setprecision(1);
      }
      caption << result.timings.extractMs() << " ms | " << toString(extractor->params().orb.threshold_mode) << " | "
              << (result.camera_moving ? "moving" : "still");
      drawAnnotated(result.image, result.keypoints, result.cell_thresholds, caption.str(), draw,
                    cv::Mat(gray.rows, gray.cols, CV_8UC3, out->data.data(), out->step));
      annotated_pub_.publish(out);
    }
  }

  // The enhancement's status of the image with this stamp, when EnhanceNodelet sent one.
  EnhanceStatus::ConstPtr statusOf(const ros::Time& stamp) const {
    const std::vector<EnhanceStatus::ConstPtr> same = statuses_.getInterval(stamp, stamp);
    return same.empty() ? nullptr : same.back();
  }

  ros::Publisher keypoints_pub_;
  // The subscriber before the cache it feeds: members are destroyed in reverse order, and the
  // cache's destructor disconnects from the subscriber, which must still exist then.
  message_filters::Subscriber<EnhanceStatus> status_sub_;
  message_filters::Cache<EnhanceStatus> statuses_{32};
  image_transport::Publisher annotated_pub_;
  ros::Publisher address_pub_;
  std::mutex params_mutex_;
  std::shared_ptr<const OrbExtractor> extractor_ = std::make_shared<const OrbExtractor>(withoutEnhancement());
  DrawOptions draw_;
};

}  // namespace enhanced_orb

PLUGINLIB_EXPORT_CLASS(enhanced_orb::ExtractNodelet, nodelet::Nodelet)
