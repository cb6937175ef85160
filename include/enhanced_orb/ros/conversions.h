// ROS <-> core conversions shared by the nodelets, tools and tests.
#ifndef ENHANCED_ORB_ROS_CONVERSIONS_H
#define ENHANCED_ORB_ROS_CONVERSIONS_H

#include <cstdint>
#include <string>

#include <cv_bridge/cv_bridge.h>
#include <sensor_msgs/Image.h>
#include <std_msgs/Header.h>
#include <opencv2/core.hpp>

#include "enhanced_orb/KeypointArray.h"
#include "enhanced_orb/orb_extractor.h"

namespace enhanced_orb {

// An input image turned into 8-bit gray, or the reason it cannot be.
struct GrayImage {
  cv::Mat gray;                           // valid when error is empty; may share the message's buffer
  std::string error;                      // what is wrong with the message, for the log
  std::string reason;                     // a short key of the kind of error ("encoding:32FC1", "data"), for throttling
  cv_bridge::CvImageConstPtr keep_alive;  // owns what `gray` points into, when cv_bridge converted
};

// Checks size, step and data length against width x height x encoding, then converts to gray:
// mono8 and 8UC1 without a copy; mono16 and 16UC1 scaled by 1/257; bgr8, rgb8, bgra8, rgba8 by
// luma; 8-bit Bayer and yuv422 through cv_bridge. Everything else is rejected.
GrayImage toGrayImage(const sensor_msgs::ImageConstPtr& msg);

// True for the encodings toGrayImage accepts.
bool isSupportedEncoding(const std::string& encoding);

// The message of an extraction; `header` is the image's.
KeypointArrayPtr toMessage(const Extraction& extraction, const std_msgs::Header& header, const Params& params);

}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_ROS_CONVERSIONS_H
