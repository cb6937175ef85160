// File handling the tools share: image sizes read from file headers before decoding, a pixel limit,
// outputs written under a temporary name and renamed when complete, and same-file checks.
#ifndef ENHANCED_ORB_EVALUATION_FILES_H
#define ENHANCED_ORB_EVALUATION_FILES_H

#include <cstdint>
#include <fstream>
#include <optional>
#include <string>

#include <opencv2/core.hpp>

#include "enhanced_orb/orb_extractor.h"

namespace enhanced_orb {
namespace evaluation {

// Width and height from the header of a PNG, JPEG, PGM/PPM or BMP file, without decoding it;
// nullopt for another format or a header that cannot be read.
std::optional<cv::Size> imageSizeFromHeader(const std::string& path);

// Reads an image as 8-bit gray, refusing one over `max_pixels` (by its header where the format
// allows, else after decoding). On failure returns an empty Mat and sets `error` to a message that
// names the file (and the size, for a refused one).
cv::Mat readGrayChecked(const std::string& path, std::int64_t max_pixels, std::string& error);

// Whether two paths name the same file (one may not exist yet: then compared after normalising).
bool sameFile(const std::string& a, const std::string& b);

// A file written under a temporary name beside `path` (same folder and extension, so that writers
// that choose their format by extension still work) and renamed to `path` by commit(); a file never
// committed is removed when the object goes, so nothing half-written is left behind.
class AtomicFile {
public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& temporary() const { return temporary_; }
  const std::string& path() const { return path_; }
  // Renames the temporary file to `path`; throws std::runtime_error when it cannot.
  void commit();

private:
  std::string path_;
  std::string temporary_;
  bool committed_ = false;
};

// A text file (the tools' CSV files) written through out() under a temporary name, as AtomicFile.
// The constructor throws when the file cannot be opened; commit() throws when a write failed
// instead of renaming a partial file.
class AtomicTextFile {
public:
  explicit AtomicTextFile(const std::string& path);
  std::ostream& out() { return out_; }
  void commit();

private:
  AtomicFile file_;
  std::ofstream out_;
};

}  // namespace evaluation
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_EVALUATION_FILES_H
