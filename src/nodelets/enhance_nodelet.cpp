// enhanced_orb/EnhanceNodelet: image -> image_enhanced (mono8, same header), section III-A.
#include <memory>
#include <mutex>

#include <dynamic_reconfigure/server.h>
#include <sensor_msgs/image_encodings.h>
#include <boost/make_shared.hpp>
#include <pluginlib/class_list_macros.hpp>

#include "enhanced_orb/EnhanceConfig.h"
#include "enhanced_orb/enhance.h"
#include "image_nodelet.h"

namespace enhanced_orb {

class EnhanceNodelet : public ImageNodelet {
private:
  // ~preset (read at start) gives every parameter not set otherwise its value.
  void seedPreset() {
    ros::NodeHandle& pnh = getPrivateNodeHandle();
    const std::string name = pnh.param<std::string>("preset", "default");
    Preset preset = Preset::kDefault;
    if (!parsePreset(name, preset)) {
      NODELET_ERROR("preset '%s' is not default or paper; using default", name.c_str());
    }
    const EnhanceParams e = Params::preset(preset).enhance;
    auto seed = [&pnh](const char* key, const auto& value) {
      if (!pnh.hasParam(key)) {
        pnh.setParam(key, value);
      }
    };
    seed("tone_curve", std::string(toString(e.tone_curve)));
    seed("tone_tiles", e.tone_tiles);
    seed("alpha", e.alpha);
    seed("tau", e.tau);
    seed("beta", e.beta);
    seed("sharpening", e.sharpening);
    seed("blur_ksize", e.blur_ksize);
    seed("blur_sigma", e.blur_sigma);
    seed("std_threshold", e.std_threshold);
    seed("gamma_mode", std::string(toString(e.gamma_mode)));
    NODELET_INFO("preset %s", toString(preset));
  }

  void advertiseOutputs() override {
    seedPreset();
    pub_ = transport().advertise("image_enhanced", queueSize(), connectCallback(), connectCallback());
    address_pub_ = advertiseAddress("output_address");
    server_ = std::make_unique<dynamic_reconfigure::Server<EnhanceConfig>>(config_mutex_, getPrivateNodeHandle());
    server_->setCallback([this](EnhanceConfig& config, uint32_t) { reconfigure(config); });
  }

  bool outputsHaveSubscribers() const override { return pub_.getNumSubscribers() > 0; }

  void reconfigure(EnhanceConfig& config) {
    if (config.blur_ksize % 2 == 0) {
      NODELET_WARN("blur_ksize = %d must be odd; using %d", config.blur_ksize, config.blur_ksize + 1);
      config.blur_ksize += 1;
    }
    EnhanceParams p;
    p.tone_tiles = config.tone_tiles;
    p.alpha = config.alpha;
    p.tau = config.tau;
    p.beta = config.beta;
    p.sharpening = config.sharpening;
    p.blur_ksize = config.blur_ksize;
    p.blur_sigma = config.blur_sigma;
    p.std_threshold = config.std_threshold;
    if (!parseToneCurve(config.tone_curve, p.tone_curve)) {
      NODELET_WARN("tone_curve '%s' is not equalize or gamma; keeping '%s'", config.tone_curve.c_str(),
                   toString(params_.tone_curve));
      p.tone_curve = params_.tone_curve;
    }
    if (!parseGammaMode(config.gamma_mode, p.gamma_mode)) {
      NODELET_WARN("gamma_mode '%s' is not auto, always or never; keeping '%s'", config.gamma_mode.c_str(),
                   toString(params_.gamma_mode));
      p.gamma_mode = params_.gamma_mode;
    }
    const std::vector<std::string> problems = validate(p);
    if (!problems.empty()) {
      NODELET_WARN("parameters rejected, keeping the previous ones: %s", joinMessages(problems).c_str());
      return;
    }
    Params all;
    all.enhance = p;
    all.enhance_enabled = config.enabled;
    warnInactive(all, {{"tone_curve", config.tone_curve},
                       {"tone_tiles", std::to_string(config.tone_tiles)},
                       {"alpha", std::to_string(config.alpha)},
                       {"tau", std::to_string(config.tau)},
                       {"beta", std::to_string(config.beta)},
                       {"sharpening", std::to_string(config.sharpening)},
                       {"std_threshold", std::to_string(config.std_threshold)},
                       {"gamma_mode", config.gamma_mode}});
    std::lock_guard<std::mutex> lock(params_mutex_);
    params_ = p;
    enabled_ = config.enabled;
  }

  void process(const sensor_msgs::ImageConstPtr& msg, const cv::Mat& gray) override {
    EnhanceParams params;
    bool enabled = true;
    {
      std::lock_guard<std::mutex> lock(params_mutex_);
      params = params_;
      enabled = enabled_;
    }
    if (!enabled && msg->encoding == sensor_msgs::image_encodings::MONO8) {
      pub_.publish(msg);  // nothing to do: hand on the very same message
      publishAddress(address_pub_, *msg);
      return;
    }
    // Build the output in its message, so that it is published without a copy.
    auto out = boost::make_shared<sensor_msgs::Image>();
    out->header = msg->header;
    out->encoding = sensor_msgs::image_encodings::MONO8;
    out->height = static_cast<uint32_t>(gray.rows);
    out->width = static_cast<uint32_t>(gray.cols);
    out->step = out->width;
    out->data.resize(static_cast<size_t>(out->step) * out->height);
    cv::Mat view(gray.rows, gray.cols, CV_8UC1, out->data.data(), out->step);
    if (enabled) {
      enhance(gray, params, view);
    } else {
      gray.copyTo(view);
    }
    pub_.publish(out);
    publishAddress(address_pub_, *out);
  }

  image_transport::Publisher pub_;
  ros::Publisher address_pub_;
  boost::recursive_mutex config_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<EnhanceConfig>> server_;
  std::mutex params_mutex_;
  EnhanceParams params_;
  bool enabled_ = true;
};

}  // namespace enhanced_orb

PLUGINLIB_EXPORT_CLASS(enhanced_orb::EnhanceNodelet, nodelet::Nodelet)
