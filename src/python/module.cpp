// _enhanced_orb: the C++ half of the Python package `enhanced_orb` (python/enhanced_orb holds the
// cv2-style half: cv2.KeyPoint lists, cv2.ORB_create's keywords). Images come in as numpy arrays
// viewed in place (no copy where the rows are contiguous); keypoints go out and come in as N x 7
// float64 arrays (x, y, size, angle, response, octave, class_id), which hold every field of a
// cv::KeyPoint exactly; descriptors as N x 32 uint8 arrays. Bad input raises TypeError or
// ValueError naming what is wrong; nothing reaches the interpreter as a crash.
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <opencv2/imgproc.hpp>

#include "enhanced_orb/enhance.h"
#include "enhanced_orb/feature2d.h"
#include "enhanced_orb/orb_extractor.h"
#include "enhanced_orb/params.h"

namespace py = pybind11;

namespace {

constexpr int kKeypointColumns = 7;

// A view of a numpy image as a cv::Mat: uint8, 2-D, or 3-D with 1, 3 (BGR) or 4 (BGRA) channels,
// each row's pixels contiguous (any row stride: a slice of a larger image is viewed, not copied).
cv::Mat viewOf(const py::array& array, const char* what, bool colour_allowed) {
  if (!py::isinstance<py::array_t<std::uint8_t>>(array)) {
    throw py::type_error(std::string(what) + " must be a uint8 array, got dtype " +
                         py::str(array.dtype()).cast<std::string>());
  }
  const py::ssize_t ndim = array.ndim();
  const int channels = ndim == 3 ? static_cast<int>(array.shape(2)) : 1;
  if (ndim != 2 && !(ndim == 3 && (channels == 1 || (colour_allowed && (channels == 3 || channels == 4))))) {
    std::string shape;
    for (py::ssize_t i = 0; i < ndim; ++i) {
      shape += (i ? " x " : "") + std::to_string(array.shape(i));
    }
    throw py::value_error(std::string(what) + " must be " +
                          (colour_allowed ? "H x W (gray), H x W x 3 (BGR) or H x W x 4 (BGRA)" : "H x W") +
                          ", got shape " + (shape.empty() ? "()" : shape));
  }
  const py::ssize_t rows = array.shape(0), cols = array.shape(1);
  if (rows == 0 || cols == 0) {
    throw py::value_error(std::string(what) + " is empty (" + std::to_string(rows) + " x " + std::to_string(cols) +
                          ")");
  }
  if (rows * cols > enhanced_orb::kMaxImagePixels) {
    throw py::value_error(std::string(what) + " has " + std::to_string(rows * cols) + " pixels, more than the " +
                          std::to_string(enhanced_orb::kMaxImagePixels) + " taken");
  }
  const bool rows_contiguous =
      array.strides(1) == channels && (ndim == 2 || array.strides(2) == 1) && array.strides(0) >= cols * channels;
  if (!rows_contiguous) {
    throw py::value_error(std::string(what) +
                          " is not contiguous within its rows (a strided or transposed view): pass "
                          "numpy.ascontiguousarray() of it");
  }
  return cv::Mat(static_cast<int>(rows), static_cast<int>(cols), CV_8UC(channels), const_cast<void*>(array.data()),
                 static_cast<size_t>(array.strides(0)));
}

cv::Mat maskOf(const py::object& mask, const cv::Mat& image) {
  if (mask.is_none()) {
    return cv::Mat();
  }
  if (!py::isinstance<py::array>(mask)) {
    throw py::type_error("mask must be None or a uint8 array");
  }
  cv::Mat view = viewOf(mask.cast<py::array>(), "mask", false);
  if (view.size() != image.size()) {
    throw py::value_error("mask is " + std::to_string(view.rows) + " x " + std::to_string(view.cols) + ", the image " +
                          std::to_string(image.rows) + " x " + std::to_string(image.cols));
  }
  return view;
}

py::array_t<double> keypointArray(const std::vector<cv::KeyPoint>& keypoints) {
  py::array_t<double> out({static_cast<py::ssize_t>(keypoints.size()), static_cast<py::ssize_t>(kKeypointColumns)});
  auto a = out.mutable_unchecked<2>();
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const cv::KeyPoint& k = keypoints[i];
    const double row[kKeypointColumns] = {
        k.pt.x, k.pt.y, k.size, k.angle, k.response, static_cast<double>(k.octave), static_cast<double>(k.class_id)};
    for (int c = 0; c < kKeypointColumns; ++c) {
      a(static_cast<py::ssize_t>(i), c) = row[c];
    }
  }
  return out;
}

std::vector<cv::KeyPoint> keypointsOf(const py::array_t<double, py::array::c_style | py::array::forcecast>& array) {
  if (array.ndim() != 2 || array.shape(1) != kKeypointColumns) {
    throw py::value_error("keypoints must be an N x 7 array (x, y, size, angle, response, octave, class_id)");
  }
  auto a = array.unchecked<2>();
  std::vector<cv::KeyPoint> keypoints(static_cast<size_t>(array.shape(0)));
  for (size_t i = 0; i < keypoints.size(); ++i) {
    const auto r = static_cast<py::ssize_t>(i);
    keypoints[i] = cv::KeyPoint(static_cast<float>(a(r, 0)), static_cast<float>(a(r, 1)), static_cast<float>(a(r, 2)),
                                static_cast<float>(a(r, 3)), static_cast<float>(a(r, 4)), static_cast<int>(a(r, 5)),
                                static_cast<int>(a(r, 6)));
  }
  return keypoints;
}

// None for no descriptors, as cv2 gives.
py::object descriptorArray(const cv::Mat& descriptors) {
  if (descriptors.empty()) {
    return py::none();
  }
  py::array_t<std::uint8_t> out(
      {static_cast<py::ssize_t>(descriptors.rows), static_cast<py::ssize_t>(descriptors.cols)});
  for (int r = 0; r < descriptors.rows; ++r) {
    std::copy(descriptors.ptr<std::uint8_t>(r), descriptors.ptr<std::uint8_t>(r) + descriptors.cols,
              out.mutable_data(r, 0));
  }
  return std::move(out);
}

// A preset, then each parameter by its ROS name from text (the Python half turns values into
// text); every problem in one ValueError, each naming its parameter.
enhanced_orb::Params paramsOf(const std::string& preset, const std::map<std::string, std::string>& values) {
  enhanced_orb::Params params;
  try {
    params = enhanced_orb::presetParams(preset);
  } catch (const std::invalid_argument& e) {
    throw py::value_error(e.what());
  }
  std::vector<std::string> problems;
  for (const auto& [name, text] : values) {
    const std::string problem = enhanced_orb::setParam(params, name, text);
    if (!problem.empty()) {
      problems.push_back(problem);
    }
  }
  const std::vector<std::string> invalid = enhanced_orb::validate(params);
  problems.insert(problems.end(), invalid.begin(), invalid.end());
  if (!problems.empty()) {
    throw py::value_error(enhanced_orb::joinMessages(problems));
  }
  return params;
}

cv::Mat grayOf(const cv::Mat& image) {
  if (image.channels() == 1) {
    return image.reshape(1);
  }
  cv::Mat gray;
  cv::cvtColor(image, gray, image.channels() == 3 ? cv::COLOR_BGR2GRAY : cv::COLOR_BGRA2GRAY);
  return gray;
}

// enhanced_orb::ORB behind the Python ORB: one stream of images, judged in order.
class PyOrb {
public:
  explicit PyOrb(const enhanced_orb::Params& params) : orb_(enhanced_orb::ORB::create(params)) {}

  py::tuple detectAndCompute(const py::array& image, const py::object& mask, bool describe) {
    const cv::Mat view = viewOf(image, "image", true);
    const cv::Mat mask_view = maskOf(mask, view);
    std::vector<cv::KeyPoint> keypoints;
    cv::Mat descriptors;
    {
      py::gil_scoped_release release;
      if (describe) {
        orb_->detectAndCompute(view, mask_view, keypoints, descriptors);
      } else {
        orb_->detect(view, keypoints, mask_view);
      }
    }
    return py::make_tuple(keypointArray(keypoints), describe ? descriptorArray(descriptors) : py::none());
  }

  py::tuple compute(const py::array& image, const py::array_t<double, py::array::c_style | py::array::forcecast>& kps) {
    const cv::Mat view = viewOf(image, "image", true);
    std::vector<cv::KeyPoint> keypoints = keypointsOf(kps);
    cv::Mat descriptors;
    {
      py::gil_scoped_release release;
      orb_->compute(view, keypoints, descriptors);
    }
    return py::make_tuple(keypointArray(keypoints), descriptorArray(descriptors));
  }

  void clear() { orb_->clear(); }
  bool cameraMoving() const { return orb_->cameraMoving(); }
  std::map<std::string, std::string> params() const {
    std::map<std::string, std::string> out;
    for (const std::string& name : enhanced_orb::paramNames()) {
      out[name] = enhanced_orb::paramText(orb_->params(), name).value_or("");
    }
    return out;
  }

private:
  cv::Ptr<enhanced_orb::ORB> orb_;
};

py::tuple enhanceImage(const py::array& image, const std::string& preset,
                       const std::map<std::string, std::string>& values) {
  const enhanced_orb::Params params = paramsOf(preset, values);
  const cv::Mat gray = grayOf(viewOf(image, "image", true));
  enhanced_orb::EnhanceResult result;
  {
    py::gil_scoped_release release;
    result = enhanced_orb::enhance(gray, params.enhance);
  }
  py::array_t<std::uint8_t> out(
      {static_cast<py::ssize_t>(result.image.rows), static_cast<py::ssize_t>(result.image.cols)});
  for (int r = 0; r < result.image.rows; ++r) {
    std::copy(result.image.ptr<std::uint8_t>(r), result.image.ptr<std::uint8_t>(r) + result.image.cols,
              out.mutable_data(r, 0));
  }
  py::dict status;
  status["lambda"] = result.lambda;
  status["mean_gray"] = result.mean_gray;
  status["poor_quality"] = result.poor_quality;
  status["inverted"] = result.inverted;
  return py::make_tuple(out, status);
}

py::list paramTable() {
  py::list rows;
  for (const enhanced_orb::ParamInfo& info : enhanced_orb::paramTable()) {
    py::dict row;
    row["name"] = info.name;
    row["type"] = info.type;
    row["range"] = info.has_range ? py::object(py::make_tuple(info.lo, info.hi)) : py::object(py::none());
    row["default"] = info.default_text;
    row["meaning"] = info.meaning;
    rows.append(row);
  }
  return rows;
}

}  // namespace

PYBIND11_MODULE(_enhanced_orb, m) {
  m.doc() = "enhanced_orb's C++ core; use the enhanced_orb package (ORB_create, enhance, params)";
  py::class_<PyOrb>(m, "Orb")
      .def(py::init([](const std::string& preset, const std::map<std::string, std::string>& values) {
             return PyOrb(paramsOf(preset, values));
           }),
           py::arg("preset"), py::arg("values"))
      .def("detect_and_compute", &PyOrb::detectAndCompute, py::arg("image"), py::arg("mask"), py::arg("describe"))
      .def("compute", &PyOrb::compute, py::arg("image"), py::arg("keypoints"))
      .def("clear", &PyOrb::clear)
      .def_property_readonly("camera_moving", &PyOrb::cameraMoving)
      .def("params", &PyOrb::params);
  m.def("enhance", &enhanceImage, py::arg("image"), py::arg("preset"), py::arg("values"));
  m.def("param_table", &paramTable);
  m.def("preset_names", [] { return std::vector<std::string>{"default", "motion", "stretch", "paper", "baseline"}; });
  m.attr("DESCRIPTOR_BYTES") = enhanced_orb::kDescriptorBytes;
}
