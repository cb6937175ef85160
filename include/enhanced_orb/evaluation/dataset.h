// One reader for the data the evaluation and the tools use: EuRoC ASL sequences, image folders and
// image pairs with a ground truth (the lighting sets' pairs.csv). No ROS: bags are read by the tools.
#ifndef ENHANCED_ORB_EVALUATION_DATASET_H
#define ENHANCED_ORB_EVALUATION_DATASET_H

#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "enhanced_orb/evaluation/metrics.h"

namespace enhanced_orb {
namespace evaluation {

// Raised for unreadable or malformed dataset files; the message names the file, the line and the value.
struct DatasetError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// One line of a CSV file: its number (from 1) and its comma-separated fields, trimmed of spaces.
struct CsvRow {
  int line = 0;
  std::vector<std::string> fields;
};

// The rows of a CSV file, '#' comment lines and empty lines skipped. Throws DatasetError when the
// file is missing or is not a file.
std::vector<CsvRow> readCsv(const std::string& file);

// Field `column` of `row` as a whole number / a finite number; throws DatasetError naming the file,
// the line, the field's name and its text when it is not one.
std::int64_t csvInteger(const std::string& file, const CsvRow& row, size_t column, const std::string& name);
double csvNumber(const std::string& file, const CsvRow& row, size_t column, const std::string& name);

// One image of a camera stream: its file and timestamp [ns] (0 when unknown).
struct FrameRef {
  std::string path;
  std::int64_t stamp = 0;
};

// A EuRoC sequence in ASL layout (DIR or DIR/mav0).
struct EurocSequence {
  std::string mav0;                      // the mav0 folder
  std::vector<FrameRef> frames;          // listed in <camera>/data.csv and present on disk
  std::vector<std::string> missing;      // listed but absent
  std::optional<Camera> camera;          // <camera>/sensor.yaml
  std::optional<Trajectory> trajectory;  // state_groundtruth_estimate0
};

// Reads <dir>/[mav0/]<camera>/data.csv ("#timestamp [ns],filename", spaces after commas allowed).
// Throws DatasetError when the CSV is missing, is not a file, or has a malformed line.
EurocSequence readEuroc(const std::string& dir, const std::string& camera = "cam0");

// The .png/.jpg/.jpeg/.pgm/.bmp/.tif files of a folder, in name order. Throws DatasetError when
// `dir` is not a folder.
std::vector<FrameRef> readImageFolder(const std::string& dir);

// Two images of one scene and how their points correspond.
struct ImagePair {
  std::string set;        // e.g. exposure_hdrps
  std::string sequence;   // the scene
  std::string reference;  // path
  std::string target;     // path
  double mean_reference = 0.0;
  double mean_target = 0.0;
  cv::Matx33d homography = cv::Matx33d::eye();  // reference -> target ("identity" pairs: eye)
};

// Reads <dir>/pairs.csv, whose header names the columns (seq, ref, target, mean_ref, mean_target
// and gt are required, others ignored), with image paths relative to `dir`; gt is "identity" or the name of a file
// holding a 3x3 homography (9 numbers, row-major) beside pairs.csv. Throws DatasetError naming file, line and value.
std::vector<ImagePair> readPairs(const std::string& dir);

// Reads an 8-bit gray image; empty when it cannot be decoded.
cv::Mat readGray(const std::string& path);

}  // namespace evaluation
}  // namespace enhanced_orb

#endif  // ENHANCED_ORB_EVALUATION_DATASET_H
