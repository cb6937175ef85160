// enhanced_orb/EnhanceNodelet: image -> image_enhanced (mono8, same header), section III-A.
#include <chrono>
#include <memory>
#include <mutex>

#include <dynamic_reconfigure/server.h>
#include <sensor_msgs/image_encodings.h>
#include <boost/make_shared.hpp>
#include <pluginlib/class_list_macros.hpp>

#include "enhanced_orb/EnhanceConfig.h"
#include "enhanced_orb/EnhanceStatus.h"
#include "enhanced_orb/enhance.h"
#include "image_nodelet.h"

namespace enhanced_orb {

class EnhanceNodelet : public ImageNodelet {
private:
  void advertiseOutputs() override {
    warnWrongTypes(configTypes<EnhanceConfig>());
    seedPreset<EnhanceConfig>();
    pub_ = transport().advertise("image_enhanced", queueSize(), connectCallback(), connectCallback());
    status_pub_ = getNodeHandle().advertise<EnhanceStatus>("enhance_status", queueSize());
    address_pub_ = advertiseAddress("output_address");
    server_ = std::make_unique<dynamic_reconfigure::Server<EnhanceConfig>>(config_mutex_, getPrivateNodeHandle());
    server_->setCallback([this](EnhanceConfig& config, uint32_t) {
      try {
        reconfigure(config);
      } catch (const std::exception& e) {
        NODELET_ERROR("reconfiguration failed, keeping the previous parameters: %s", e.what());
        config = valid_;
      }
    });
  }

  bool outputsHaveSubscribers() const override { return pub_.getNumSubscribers() > 0; }

  static EnhanceParams toParams(const EnhanceConfig& config) {
    EnhanceParams p;
    parseToneCurve(config.tone_curve, p.tone_curve);
    p.alpha = config.alpha;
    p.tau = config.tau;
    p.beta = config.beta;
    p.sharpening = config.sharpening;
    p.blur_ksize = config.blur_ksize;
    p.blur_sigma = config.blur_sigma;
    p.std_threshold = config.std_threshold;
    parseGammaMode(config.gamma_mode, p.gamma_mode);
    p.threads = config.enhance_threads;
    return p;
  }

  // A refused value is set back to the last valid one in `config`, which the server then reports:
  // what dynamic_reconfigure shows is what runs, and one bad value never blocks the others.
  void reconfigure(EnhanceConfig& config) {
    if (config.blur_ksize % 2 == 0) {
      NODELET_WARN("blur_ksize = %d must be odd; using %d", config.blur_ksize, config.blur_ksize + 1);
      config.blur_ksize += 1;
    }
    std::vector<std::string> problems;
    ToneCurve curve;
    if (!parseToneCurve(config.tone_curve, curve)) {
      problems.push_back("tone_curve '" + config.tone_curve + "' is not " + toneCurveNames());
    }
    GammaMode mode;
    if (!parseGammaMode(config.gamma_mode, mode)) {
      problems.push_back("gamma_mode '" + config.gamma_mode + "' is not " + gammaModeNames());
    }
    for (const std::string& problem : validate(toParams(config))) {
      problems.push_back(problem);
    }
    restoreRefused(config, valid_, problems);
    const EnhanceParams p = toParams(config);
    if (!validate(p).empty()) {  // only if the restored values are invalid together
      NODELET_ERROR("parameters rejected, keeping the previous ones: %s", joinMessages(validate(p)).c_str());
      config = valid_;
      return;
    }
    Params all;
    all.enhance = p;
    all.enhance_enabled = config.enhance;
    warnInactive(all, configValues(config));
    valid_ = config;
    std::lock_guard<std::mutex> lock(params_mutex_);
    params_ = p;
    enabled_ = config.enhance;
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
    const auto start = std::chrono::steady_clock::now();
    EnhanceResult result;
    if (enabled) {
      std::lock_guard<std::mutex> lock(workspace_mutex_);  // one frame at a time uses the buffers
      result = enhance(gray, params, workspace_, view);
    } else {
      gray.copyTo(view);
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    publishStatus(msg->header, gray, params, enabled, result, ms);  // first: the extractor looks it up by stamp
    pub_.publish(out);
    publishAddress(address_pub_, *out);
  }

  void publishStatus(const std_msgs::Header& header, const cv::Mat& gray, const EnhanceParams& params, bool enabled,
                     const EnhanceResult& result, double ms) {
    auto status = boost::make_shared<EnhanceStatus>();
    status->header = header;
    status->lambda = static_cast<float>(enabled ? result.lambda : imageLambda(gray));
    status->mean_gray = static_cast<float>(enabled ? result.mean_gray : cv::mean(gray)[0]);
    status->poor_quality = enabled && result.poor_quality;
    status->inverted = result.inverted;
    status->tone_curve = toString(params.tone_curve);
    status->gamma_mode = enabled ? toString(params.gamma_mode) : "never";
    status->enhance_ms = static_cast<float>(ms);
    {
      std::lock_guard<std::mutex> lock(status_mutex_);
      last_status_ = *status;
    }
    status_pub_.publish(status);
  }

  void addDiagnostics(diagnostic_updater::DiagnosticStatusWrapper& status) override {
    std::lock_guard<std::mutex> lock(status_mutex_);
    status.add("last lambda", last_status_.lambda);
    status.add("last mean gray", last_status_.mean_gray);
    status.add("tone curve", last_status_.tone_curve + " (gamma_mode " + last_status_.gamma_mode + ")");
    status.add("tone curve applied to the last image", static_cast<bool>(last_status_.poor_quality));
    status.add("last image inverted", static_cast<bool>(last_status_.inverted));
  }

  image_transport::Publisher pub_;
  ros::Publisher status_pub_;
  std::mutex status_mutex_;
  EnhanceStatus last_status_;
  ros::Publisher address_pub_;
  boost::recursive_mutex config_mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<EnhanceConfig>> server_;
  std::mutex params_mutex_;
  EnhanceConfig valid_ = EnhanceConfig::__getDefault__();  // the last configuration applied
  EnhanceParams params_ = toParams(valid_);
  bool enabled_ = true;
  std::mutex workspace_mutex_;
  EnhanceWorkspace workspace_;  // the enhancement's buffers, reused frame after frame
};

}  // namespace enhanced_orb

PLUGINLIB_EXPORT_CLASS(enhanced_orb::EnhanceNodelet, nodelet::Nodelet)
