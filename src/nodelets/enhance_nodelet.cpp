// enhanced_orb/EnhanceNodelet: image -> image_enhanced (mono8, same header), section III-A. With
// camera_motion auto it judges, as ExtractNodelet does, whether the camera moves: a moving camera's
// frames are enhanced with moving_gamma_mode (Params::forFrame).
#include <chrono>
#include <memory>
#include <mutex>

#include <sensor_msgs/image_encodings.h>
#include <boost/make_shared.hpp>
#include <pluginlib/class_list_macros.hpp>

#include "enhanced_orb/EnhanceConfig.h"
#include "enhanced_orb/EnhanceStatus.h"
#include "enhanced_orb/enhance.h"
#include "reconfigurable_nodelet.h"

namespace enhanced_orb {

class EnhanceNodelet : public ReconfigurableNodelet<EnhanceConfig> {
private:
  void advertiseOutputs() override {
    startReconfigure();
    pub_ = transport().advertise("image_enhanced", queueSize(), connectCallback(), connectCallback());
    status_pub_ = getNodeHandle().advertise<EnhanceStatus>("enhance_status", queueSize());
    address_pub_ = advertiseAddress("output_address");
  }

  bool outputsHaveSubscribers() const override { return pub_.getNumSubscribers() > 0; }

  const Fields& configFields() const override { return enhanceConfigFields(); }

  void adjust(EnhanceConfig& config) override {
    if (config.blur_ksize % 2 == 0) {
      NODELET_WARN("blur_ksize = %d must be odd; using %d", config.blur_ksize, config.blur_ksize + 1);
      config.blur_ksize += 1;
    }
  }

  void apply(const EnhanceConfig& /*config*/, const Params& params) override {
    std::lock_guard<std::mutex> lock(params_mutex_);
    params_ = params;
  }

  void process(const sensor_msgs::ImageConstPtr& msg, const cv::Mat& gray, double /*convert_ms*/) override {
    Params all;
    {
      std::lock_guard<std::mutex> lock(params_mutex_);
      all = params_;
    }
    const bool enabled = all.enhance_enabled;
    // Judged only where the enhancement depends on the stream.
    const bool judge = all.enhancementJudgesStream();
    const StreamJudgment stream = judgeMotion(msg->header.stamp, gray, judge);
    const bool camera_moving = all.movingSelection(stream.moving);
    const EnhanceParams params = all.forFrame(stream.moving, stream.stream_lambda).enhance;
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
    publishStatus(msg->header, gray, params, enabled, camera_moving, result,
                  ms);  // first: the extractor looks it up by stamp
    pub_.publish(out);
    publishAddress(address_pub_, *out);
  }

  void publishStatus(const std_msgs::Header& header, const cv::Mat& gray, const EnhanceParams& params, bool enabled,
                     bool camera_moving, const EnhanceResult& result, double ms) {
    auto status = boost::make_shared<EnhanceStatus>();
    status->header = header;
    status->lambda = static_cast<float>(enabled ? result.lambda : imageLambda(gray));
    status->mean_gray = static_cast<float>(enabled ? result.mean_gray : cv::mean(gray)[0]);
    status->poor_quality = enabled && result.poor_quality;
    status->inverted = result.inverted;
    status->tone_curve = toString(params.tone_curve);
    status->gamma_mode = enabled ? toString(params.gamma_mode) : "never";
    status->camera_moving = camera_moving;
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
    status.add("last image judged moving", static_cast<bool>(last_status_.camera_moving));
    status.add("last image inverted", static_cast<bool>(last_status_.inverted));
  }

  image_transport::Publisher pub_;
  ros::Publisher status_pub_;
  std::mutex status_mutex_;
  EnhanceStatus last_status_;
  ros::Publisher address_pub_;
  std::mutex params_mutex_;
  Params params_;
  std::mutex workspace_mutex_;
  EnhanceWorkspace workspace_;  // the enhancement's buffers, reused frame after frame
};

}  // namespace enhanced_orb

PLUGINLIB_EXPORT_CLASS(enhanced_orb::EnhanceNodelet, nodelet::Nodelet)
