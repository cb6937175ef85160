#include "enhanced_orb/evaluation/files.h"

#include <array>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

#include <unistd.h>

#include <opencv2/imgcodecs.hpp>

namespace enhanced_orb {
namespace evaluation {
namespace {

namespace fs = std::filesystem;

std::uint32_t bigEndian(const unsigned char* p, int bytes) {
  std::uint32_t v = 0;
  for (int i = 0; i < bytes; ++i) {
    v = (v << 8) | p[i];
  }
  return v;
}

std::optional<cv::Size> pngSize(std::istream& in) {
  std::array<unsigned char, 24> h{};
  if (!in.read(reinterpret_cast<char*>(h.data()), h.size()) || std::string(h.begin() + 12, h.begin() + 16) != "IHDR") {
    return std::nullopt;
  }
  return cv::Size(static_cast<int>(bigEndian(&h[16], 4)), static_cast<int>(bigEndian(&h[20], 4)));
}

std::optional<cv::Size> jpegSize(std::istream& in) {
  in.seekg(2);
  for (int markers = 0; markers < 1000 && in; ++markers) {
    unsigned char m[4];
    if (!in.read(reinterpret_cast<char*>(m), 4) || m[0] != 0xFF) {
      return std::nullopt;
    }
    const int type = m[1];
    const int length = static_cast<int>(bigEndian(&m[2], 2));
    const bool sof = type >= 0xC0 && type <= 0xCF && type != 0xC4 && type != 0xC8 && type != 0xCC;
    if (sof) {
      unsigned char s[5];
      if (!in.read(reinterpret_cast<char*>(s), 5)) {
        return std::nullopt;
      }
      return cv::Size(static_cast<int>(bigEndian(&s[3], 2)), static_cast<int>(bigEndian(&s[1], 2)));
    }
    in.seekg(length - 2, std::ios::cur);
  }
  return std::nullopt;
}

std::optional<cv::Size> pnmSize(std::istream& in) {
  in.seekg(2);
  long values[2] = {0, 0};
  for (long& v : values) {
    int c = in.get();
    while (in && (std::isspace(c) || c == '#')) {
      if (c == '#') {
        while (in && c != '\n') {
          c = in.get();
        }
      }
      c = in.get();
    }
    if (!std::isdigit(c)) {
      return std::nullopt;
    }
    while (in && std::isdigit(c)) {
      v = v * 10 + (c - '0');
      if (v > (1L << 31)) {
        return std::nullopt;
      }
      c = in.get();
    }
  }
  return cv::Size(static_cast<int>(values[0]), static_cast<int>(values[1]));
}

std::optional<cv::Size> bmpSize(std::istream& in) {
  std::array<unsigned char, 26> h{};
  if (!in.read(reinterpret_cast<char*>(h.data()), h.size())) {
    return std::nullopt;
  }
  auto little = [&](int at) {
    return static_cast<std::int32_t>(h[at] | (h[at + 1] << 8) | (h[at + 2] << 16) | (h[at + 3] << 24));
  };
  const std::int32_t height = little(22);
  return cv::Size(little(18), height < 0 ? -height : height);
}

}  // namespace

std::optional<cv::Size> imageSizeFromHeader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  unsigned char magic[8] = {};
  if (!in.read(reinterpret_cast<char*>(magic), 8)) {
    return std::nullopt;
  }
  in.seekg(0);
  if (magic[0] == 0x89 && magic[1] == 'P' && magic[2] == 'N' && magic[3] == 'G') {
    return pngSize(in);
  }
  if (magic[0] == 0xFF && magic[1] == 0xD8) {
    return jpegSize(in);
  }
  if (magic[0] == 'P' && magic[1] >= '1' && magic[1] <= '6') {
    return pnmSize(in);
  }
  if (magic[0] == 'B' && magic[1] == 'M') {
    return bmpSize(in);
  }
  return std::nullopt;
}

cv::Mat readGrayChecked(const std::string& path, std::int64_t max_pixels, std::string& error) {
  error.clear();
  if (!fs::is_regular_file(path)) {
    error = path + ": " + (fs::exists(path) ? "is not a file" : "does not exist");
    return cv::Mat();
  }
  auto tooLarge = [&](cv::Size size) {
    error = path + ": " + std::to_string(size.width) + " x " + std::to_string(size.height) + " = " +
            std::to_string(static_cast<std::int64_t>(size.width) * size.height) + " pixels exceeds the limit of " +
            std::to_string(max_pixels) + " (--max-pixels)";
    return cv::Mat();
  };
  const std::optional<cv::Size> header = imageSizeFromHeader(path);
  if (header && static_cast<std::int64_t>(header->width) * header->height > max_pixels) {
    return tooLarge(*header);
  }
  cv::Mat gray;
  try {
    gray = cv::imread(path, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception& e) {
    error = path + ": cannot be decoded (" + e.what() + ")";
    return cv::Mat();
  }
  if (gray.empty()) {
    error = path + ": cannot be decoded as an image";
    return cv::Mat();
  }
  if (static_cast<std::int64_t>(gray.total()) > max_pixels) {
    return tooLarge(gray.size());
  }
  return gray;
}

bool sameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::exists(a, ec) && fs::exists(b, ec)) {
    return fs::equivalent(a, b, ec);
  }
  return fs::weakly_canonical(a, ec) == fs::weakly_canonical(b, ec);
}

AtomicFile::AtomicFile(std::string path) : path_(std::move(path)) {
  const fs::path p(path_);
  temporary_ =
      (p.parent_path() / ("." + p.stem().string() + ".part-" + std::to_string(::getpid()) + p.extension().string()))
          .string();
}

AtomicFile::~AtomicFile() {
  if (!committed_) {
    std::error_code ec;
    fs::remove(temporary_, ec);
  }
}

void AtomicFile::commit() {
  std::error_code ec;
  fs::rename(temporary_, path_, ec);
  if (ec) {
    throw std::runtime_error("cannot rename " + temporary_ + " to " + path_ + ": " + ec.message());
  }
  committed_ = true;
}

AtomicTextFile::AtomicTextFile(const std::string& path) : file_(path), out_(file_.temporary()) {
  if (!out_) {
    throw std::runtime_error("cannot write " + path);
  }
}

void AtomicTextFile::commit() {
  out_.close();
  if (!out_) {
    throw std::runtime_error("cannot write " + file_.path());
  }
  file_.commit();
}

}  // namespace evaluation
}  // namespace enhanced_orb
