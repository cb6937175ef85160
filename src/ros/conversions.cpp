#include "enhanced_orb/ros/conversions.h"

#include <sensor_msgs/image_encodings.h>
#include <boost/make_shared.hpp>

#include "enhanced_orb/enhance.h"

namespace enc = sensor_msgs::image_encodings;

namespace enhanced_orb {
namespace {

struct EncodingSpec {
  const char* name;
  int bytes_per_pixel;
  int cv_type;         // the Mat type that views the data, for the core's toGray
  PixelFormat format;  // ignored when via_cv_bridge
  bool via_cv_bridge;  // Bayer and YUV: cv_bridge converts to mono8
};

const EncodingSpec kEncodings[] = {
    {"mono8", 1, CV_8UC1, PixelFormat::kMono8, false},      {"8UC1", 1, CV_8UC1, PixelFormat::kMono8, false},
    {"mono16", 2, CV_16UC1, PixelFormat::kMono16, false},   {"16UC1", 2, CV_16UC1, PixelFormat::kMono16, false},
    {"bgr8", 3, CV_8UC3, PixelFormat::kBGR, false},         {"rgb8", 3, CV_8UC3, PixelFormat::kRGB, false},
    {"bgra8", 4, CV_8UC4, PixelFormat::kBGRA, false},       {"rgba8", 4, CV_8UC4, PixelFormat::kRGBA, false},
    {"bayer_rggb8", 1, CV_8UC1, PixelFormat::kMono8, true}, {"bayer_bggr8", 1, CV_8UC1, PixelFormat::kMono8, true},
    {"bayer_gbrg8", 1, CV_8UC1, PixelFormat::kMono8, true}, {"bayer_grbg8", 1, CV_8UC1, PixelFormat::kMono8, true},
    {"yuv422", 2, CV_8UC2, PixelFormat::kMono8, true},
};

const EncodingSpec* findEncoding(const std::string& name) {
  for (const EncodingSpec& spec : kEncodings) {
    if (name == spec.name) {
      return &spec;
    }
  }
  return nullptr;
}

GrayImage failure(const std::string& reason, const std::string& error) {
  GrayImage out;
  out.reason = reason;
  out.error = error;
  return out;
}

}  // namespace

bool isSupportedEncoding(const std::string& encoding) {
  return findEncoding(encoding) != nullptr;
}

GrayImage toGrayImage(const sensor_msgs::ImageConstPtr& msg) {
  const sensor_msgs::Image& m = *msg;
  const EncodingSpec* spec = findEncoding(m.encoding);
  if (spec == nullptr) {
    return failure("encoding:" + m.encoding, "unsupported encoding '" + m.encoding +
                                                 "' (supported: mono8, 8UC1, mono16, 16UC1, bgr8, rgb8, bgra8, rgba8, "
                                                 "bayer_*8, yuv422); image dropped");
  }
  const std::string size = std::to_string(m.width) + "x" + std::to_string(m.height);
  if (m.width == 0 || m.height == 0) {
    return failure("empty", "empty " + size + " image dropped");
  }
  if (static_cast<std::int64_t>(m.width) * m.height > kMaxImagePixels) {
    return failure("huge", size + " image dropped: more than " + std::to_string(kMaxImagePixels) + " pixels");
  }
  const std::uint64_t row_bytes = static_cast<std::uint64_t>(m.width) * spec->bytes_per_pixel;
  if (m.step < row_bytes) {
    return failure("step", "step " + std::to_string(m.step) + " is smaller than a " + m.encoding + " row of " + size +
                               " (" + std::to_string(row_bytes) + " bytes); image dropped");
  }
  const std::uint64_t needed = static_cast<std::uint64_t>(m.step) * m.height;
  if (m.data.size() < needed) {
    return failure("data", "data holds " + std::to_string(m.data.size()) + " bytes, step x height needs " +
                               std::to_string(needed) + "; image dropped");
  }
  GrayImage out;
  try {
    if (spec->via_cv_bridge) {
      out.keep_alive = cv_bridge::toCvShare(msg, enc::MONO8);
      out.gray = out.keep_alive->image;
      return out;
    }
    cv::Mat view(static_cast<int>(m.height), static_cast<int>(m.width), spec->cv_type,
                 const_cast<std::uint8_t*>(m.data.data()), m.step);
    if (m.is_bigendian && spec->bytes_per_pixel == 2) {
      cv::Mat swapped(view.size(), CV_16UC1);
      for (int y = 0; y < view.rows; ++y) {
        const std::uint16_t* in = view.ptr<std::uint16_t>(y);
        std::uint16_t* outp = swapped.ptr<std::uint16_t>(y);
        for (int x = 0; x < view.cols; ++x) {
          outp[x] = static_cast<std::uint16_t>((in[x] >> 8) | (in[x] << 8));
        }
      }
      view = swapped;
    }
    out.gray = toGray(view, spec->format);
  } catch (const std::exception& e) {
    return failure("convert:" + m.encoding, "cannot convert " + m.encoding + " " + size + " to gray: " + e.what());
  }
  return out;
}

KeypointArrayPtr toMessage(const Extraction& extraction, const std_msgs::Header& header, const Params& params) {
  auto msg = boost::make_shared<KeypointArray>();
  msg->header = header;
  msg->width = static_cast<std::uint32_t>(extraction.image.cols);
  msg->height = static_cast<std::uint32_t>(extraction.image.rows);
  msg->keypoints.resize(extraction.keypoints.size());
  for (size_t i = 0; i < extraction.keypoints.size(); ++i) {
    const cv::KeyPoint& kp = extraction.keypoints[i];
    Keypoint& out = msg->keypoints[i];
    out.x = kp.pt.x;
    out.y = kp.pt.y;
    out.size = kp.size;
    out.angle = kp.angle;
    out.response = kp.response;
    out.octave = kp.octave;
  }
  msg->descriptor_bytes = kDescriptorBytes;
  const cv::Mat& d = extraction.descriptors;
  msg->descriptors.resize(static_cast<size_t>(d.rows) * kDescriptorBytes);
  for (int r = 0; r < d.rows; ++r) {
    std::copy(d.ptr<std::uint8_t>(r), d.ptr<std::uint8_t>(r) + kDescriptorBytes,
              msg->descriptors.begin() + static_cast<std::ptrdiff_t>(r) * kDescriptorBytes);
  }
  const cv::Mat& t = extraction.cell_thresholds;
  msg->grid_size = static_cast<std::uint32_t>(t.rows);
  msg->cell_thresholds.assign(t.begin<int>(), t.end<int>());
  msg->camera_moving = extraction.camera_moving;
  msg->threshold_mode = toString(params.orb.threshold_mode);
  msg->n_levels = static_cast<std::uint32_t>(extraction.level_thresholds.size());
  msg->scale_factor = static_cast<float>(params.orb.scale_factor);
  msg->extract_ms = static_cast<float>(extraction.timings.extractMs());
  msg->judge_ms = static_cast<float>(extraction.timings.judge_ms);
  msg->total_ms = static_cast<float>(extraction.timings.totalMs());
  return msg;
}

}  // namespace enhanced_orb
