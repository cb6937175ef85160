// enhanced_orb/ExtractNodelet: image -> keypoints (KeypointArray) and image_annotated (bgr8),
// ORB with the truncated adaptive threshold (section III-B) or the original fixed threshold.
#include <iomanip>
#include <memory>
#include <mutex>
#include <sstream>

#include <dynamic_reconfigure/server.h>
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
#include "image_nodelet.h"

namespace enhanced_orb {

class ExtractNodelet : public ImageNodelet {
private:
  void advertiseOutputs() override {
    warnWrongTypes(configTypes<ExtractConfig>());
    seedPreset<ExtractConfig>();
    ros::NodeHandle& nh = getNodeHandle();
    keypoints_pub_ = nh.advertise<KeypointArray>("keypoints", queueSize(), connectCallbackRos(), connectCallbackRos());
    annotated_pub_ = transport().advertise("image_annotated", queueSize(), connectCallback(), connectCallback());
    address_pub_ = advertiseAddress("input_address");
    // The enhancement's statuses, kept by stamp (message_filters::Cache) for the caption of the
    // image with the same stamp; an image without one is drawn without it.
    status_sub_.subscribe(nh, "enhance_status", 10);
    statuses_.connectInput(status_sub_);
    server_ = std::make_unique<dynamic_reconfigure::Server<ExtractConfig>>(config_mutex_, getPrivateNodeHandle());
    server_->setCallback([this](ExtractConfig& config, uint32_t) {
      try {
        reconfigure(config);
      } catch (const std::exception& e) {
        NODELET_ERROR("reconfiguration failed, keeping the previous parameters: %s", e.what());
        config = valid_;
      }
    });
  }

  bool outputsHaveSubscribers() const override {
    return keypoints_pub_.getNumSubscribers() > 0 || annotated_pub_.getNumSubscribers() > 0;
  }

  static Params toParams(const ExtractConfig& config) {
    Params p;
    p.enhance_enabled = false;  // the input is enhanced upstream (EnhanceNodelet) or raw on purpose (baseline)
    p.threshold.c_min = config.c_min;
    p.threshold.threshold_scale = config.threshold_scale;
    p.threshold.grid_size = config.grid_size;
    p.orb.fast_threshold = config.fast_threshold;
    p.orb.max_features = config.max_features;
    p.orb.candidate_ratio = config.candidate_ratio;
    p.orb.noise_floor = config.noise_floor;
    p.orb.n_levels = config.n_levels;
    p.orb.scale_factor = config.scale_factor;
    p.orb.threads = config.threads;
    parseThresholdMode(config.threshold_mode, p.orb.threshold_mode);
    return p;
  }

  // A refused value is set back to the last valid one in `config`, which the server then reports:
  // what dynamic_reconfigure shows is what runs, and one bad value never blocks the others.
  void reconfigure(ExtractConfig& config) {
    std::vector<std::string> problems;
    ThresholdMode mode;
    if (!parseThresholdMode(config.threshold_mode, mode)) {
      problems.push_back("threshold_mode '" + config.threshold_mode + "' is not " + thresholdModeNames());
    }
    for (const std::string& problem : validate(toParams(config))) {
      problems.push_back(problem);
    }
    restoreRefused(config, valid_, problems);
    const Params p = toParams(config);
    std::shared_ptr<const OrbExtractor> extractor;
    try {
      extractor = std::make_shared<const OrbExtractor>(p);
    } catch (const std::invalid_argument& e) {  // only if the restored values are invalid together
      NODELET_ERROR("parameters rejected, keeping the previous ones: %s", e.what());
      config = valid_;
      return;
    }
    warnInactive(p, configValues(config));
    valid_ = config;
    std::lock_guard<std::mutex> lock(params_mutex_);
    extractor_ = extractor;
    draw_ = DrawOptions{config.draw_keypoints, config.draw_orientation, config.draw_grid, config.draw_text,
                        config.draw_max};
  }

  void process(const sensor_msgs::ImageConstPtr& msg, const cv::Mat& gray) override {
    publishAddress(address_pub_, *msg);
    std::shared_ptr<const OrbExtractor> extractor;
    DrawOptions draw;
    {
      std::lock_guard<std::mutex> lock(params_mutex_);
      extractor = extractor_;
      draw = draw_;
    }
    const Extraction result = extractor->extract(gray);
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
      caption << result.timings.extractMs() << " ms | " << toString(extractor->params().orb.threshold_mode);
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
  message_filters::Subscriber<EnhanceStatus> status_sub_;
  message_filters::Cache<EnhanceStatus> statuses_{32};
  image_transport::Publisher annotated_pub_;
  ros::Publisher address_pub_;
  boost::recursive_mutex config_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<ExtractConfig>> server_;
  std::mutex params_mutex_;
  ExtractConfig valid_ = ExtractConfig::__getDefault__();  // the last configuration applied
  std::shared_ptr<const OrbExtractor> extractor_ = std::make_shared<const OrbExtractor>(toParams(valid_));
  DrawOptions draw_;
};

}  // namespace enhanced_orb

PLUGINLIB_EXPORT_CLASS(enhanced_orb::ExtractNodelet, nodelet::Nodelet)
