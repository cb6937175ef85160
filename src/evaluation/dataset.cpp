#include "enhanced_orb/evaluation/dataset.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include <opencv2/imgcodecs.hpp>

namespace enhanced_orb {
namespace evaluation {
namespace {

namespace fs = std::filesystem;

std::string trim(const std::string& s) {
  size_t a = 0;
  size_t b = s.size();
  while (a < b && std::isspace(static_cast<unsigned char>(s[a]))) {
    ++a;
  }
  while (b > a && std::isspace(static_cast<unsigned char>(s[b - 1]))) {
    --b;
  }
  return s.substr(a, b - a);
}

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) {
    fields.push_back(trim(field));
  }
  return fields;
}

[[noreturn]] void fail(const fs::path& file, int line, const std::string& what) {
  throw DatasetError(file.string() + (line > 0 ? ":" + std::to_string(line) : "") + ": " + what);
}

std::ifstream openFile(const fs::path& file) {
  if (!fs::is_regular_file(file)) {
    fail(file, 0, fs::exists(file) ? "is not a file" : "does not exist");
  }
  std::ifstream in(file);
  if (!in) {
    fail(file, 0, "cannot be read");
  }
  return in;
}

template <typename T>
T parseField(const fs::path& file, int line, const std::string& name, const std::string& text) {
  std::istringstream in(text);
  T value{};
  in >> value;
  if (in.fail() || !in.eof()) {
    fail(file, line, name + " '" + text + "' is not a number");
  }
  return value;
}

}  // namespace

std::vector<CsvRow> readCsv(const std::string& file) {
  std::ifstream in = openFile(file);
  std::vector<CsvRow> rows;
  std::string text;
  for (int line = 1; std::getline(in, text); ++line) {
    text = trim(text);
    if (!text.empty() && text[0] != '#') {
      rows.push_back({line, splitCsv(text)});
    }
  }
  return rows;
}

std::int64_t csvInteger(const std::string& file, const CsvRow& row, size_t column, const std::string& name) {
  if (column >= row.fields.size()) {
    fail(file, row.line, "no field " + name);
  }
  return parseField<std::int64_t>(file, row.line, name, row.fields[column]);
}

double csvNumber(const std::string& file, const CsvRow& row, size_t column, const std::string& name) {
  if (column >= row.fields.size()) {
    fail(file, row.line, "no field " + name);
  }
  const double v = parseField<double>(file, row.line, name, row.fields[column]);
  if (!std::isfinite(v)) {
    fail(file, row.line, name + " '" + row.fields[column] + "' is not finite");
  }
  return v;
}

EurocSequence readEuroc(const std::string& dir, const std::string& camera) {
  EurocSequence seq;
  fs::path mav0 = dir;
  if (fs::is_directory(mav0 / "mav0")) {
    mav0 /= "mav0";
  }
  seq.mav0 = mav0.string();
  const std::string csv = (mav0 / camera / "data.csv").string();
  for (const CsvRow& row : readCsv(csv)) {
    if (row.fields.size() < 2 || row.fields[1].empty()) {
      fail(csv, row.line, "expected 'timestamp,filename'");
    }
    const std::int64_t stamp = csvInteger(csv, row, 0, "timestamp");
    const fs::path file = mav0 / camera / "data" / row.fields[1];
    if (fs::is_regular_file(file)) {
      seq.frames.push_back({file.string(), stamp});
    } else {
      seq.missing.push_back(file.string());
    }
  }
  seq.camera = readCamera(mav0.string(), camera);
  seq.trajectory = Trajectory::read(mav0.string());
  return seq;
}

std::vector<FrameRef> readImageFolder(const std::string& dir) {
  if (!fs::is_directory(dir)) {
    fail(dir, 0, "is not a folder");
  }
  const std::vector<std::string> extensions{".png", ".jpg", ".jpeg", ".pgm", ".bmp", ".tif", ".tiff"};
  std::vector<FrameRef> frames;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::string ext = entry.path().extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    if (entry.is_regular_file() && std::find(extensions.begin(), extensions.end(), ext) != extensions.end()) {
      frames.push_back({entry.path().string(), 0});
    }
  }
  std::sort(frames.begin(), frames.end(), [](const FrameRef& a, const FrameRef& b) { return a.path < b.path; });
  return frames;
}

std::vector<ImagePair> readPairs(const std::string& dir) {
  const fs::path csv = fs::path(dir) / "pairs.csv";
  std::ifstream in = openFile(csv);
  std::vector<ImagePair> pairs;
  std::string text;
  std::map<std::string, size_t> column;  // from the header line
  const std::vector<std::string> required{"seq", "ref", "target", "mean_ref", "mean_target", "gt"};
  for (int line = 1; std::getline(in, text); ++line) {
    text = trim(text);
    if (text.empty() || text[0] == '#') {
      continue;
    }
    const std::vector<std::string> f = splitCsv(text);
    if (column.empty()) {
      for (size_t i = 0; i < f.size(); ++i) {
        column[f[i]] = i;
      }
      for (const std::string& name : required) {
        if (!column.count(name)) {
          fail(csv, line, "the header has no column '" + name + "'");
        }
      }
      continue;
    }
    if (f.size() < column.size()) {
      fail(csv, line, "expected " + std::to_string(column.size()) + " fields, got '" + text + "'");
    }
    auto field = [&](const std::string& name) { return f[column.at(name)]; };
    ImagePair p;
    p.set = fs::path(dir).lexically_normal().filename().string();
    if (p.set.empty()) {
      p.set = fs::path(dir).lexically_normal().parent_path().filename().string();
    }
    p.sequence = field("seq");
    p.reference = (fs::path(dir) / field("ref")).string();
    p.target = (fs::path(dir) / field("target")).string();
    p.mean_reference = parseField<double>(csv, line, "mean_ref", field("mean_ref"));
    p.mean_target = parseField<double>(csv, line, "mean_target", field("mean_target"));
    if (field("gt") != "identity") {
      const fs::path h_file = fs::path(dir) / field("gt");
      std::ifstream h_in = openFile(h_file);
      for (int i = 0; i < 9; ++i) {
        if (!(h_in >> p.homography.val[i])) {
          fail(h_file, 0, "expected 9 numbers of a 3x3 homography");
        }
      }
    }
    pairs.push_back(p);
  }
  return pairs;
}

cv::Mat readGray(const std::string& path) {
  try {
    return cv::imread(path, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception&) {
    return cv::Mat();
  }
}

}  // namespace evaluation
}  // namespace enhanced_orb
