#include "linear_resize.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "kernels/pyramid_rows.h"

namespace enhanced_orb {

// OpenCV's taps for one axis (interpolationLinear in its resize.cpp): output i samples the source
// at f = s (i + 0.5) - 0.5 with s = 1 / (dst_length / src_length), in double precision (its
// software doubles round as IEEE doubles do); its second pixel weighs round(256 (f - floor f)),
// ties to even. Outputs left of the source (f < 0) take the first pixel, outputs at or right of its
// last one the last pixel: written here as taps of weight 0 on (0, 1) and of weight 256 on
// (n - 2, n - 1), which give the same values and keep every tap inside the source.
void LinearResize::taps(int src_length, int dst_length, Axis& axis) {
  axis.index.resize(static_cast<size_t>(dst_length));
  axis.weight.resize(static_cast<size_t>(dst_length));
  const double scale = 1.0 / (static_cast<double>(dst_length) / src_length);
  for (int i = 0; i < dst_length; ++i) {
    const double f = scale * (static_cast<double>(i) + 0.5) - 0.5;
    const int first = static_cast<int>(std::floor(f));
    if (first < 0) {
      axis.index[i] = 0;
      axis.weight[i] = 0;
    } else if (first >= src_length - 1) {
      axis.index[i] = src_length - 2;
      axis.weight[i] = 256;
    } else {
      axis.index[i] = first;
      axis.weight[i] = static_cast<std::uint16_t>(std::nearbyint((f - first) * 256.0));
    }
  }
}

void LinearResize::plan(cv::Size from, cv::Size to) {
  if (from == from_ && to == to_) {
    return;
  }
  taps(from.width, to.width, columns_);
  taps(from.height, to.height, rows_);
  // Vector blocks of 8 outputs while their pixels fit in 16 bytes that stay inside the row.
  block_start_.clear();
  block_shuffle_.clear();
  for (int x = 0; x + 8 <= to.width; x += 8) {
    const int start = columns_.index[x];
    if (columns_.index[x + 7] + 1 - start > 15 || start + 16 > from.width) {
      break;
    }
    block_start_.push_back(start);
    for (int k = 0; k < 8; ++k) {
      block_shuffle_.push_back(static_cast<std::uint8_t>(columns_.index[x + k] - start));
      block_shuffle_.push_back(static_cast<std::uint8_t>(columns_.index[x + k] - start + 1));
    }
  }
  lines_[0].resize(static_cast<size_t>(to.width));
  lines_[1].resize(static_cast<size_t>(to.width));
  from_ = from;
  to_ = to;
}

void LinearResize::operator()(const cv::Mat& src, cv::Mat& dst, cv::Size size, SimdLevel level) {
  CV_Assert(src.type() == CV_8UC1 && size.width > 0 && size.height > 0);
  const bool area = 2 * size.width == src.cols && 2 * size.height == src.rows;
  if (!kernels::hasVectorLinearKernels(level) || area || src.cols < 2 || src.rows < 2 || size == src.size()) {
    cv::resize(src, dst, size, 0, 0, cv::INTER_LINEAR_EXACT);
    return;
  }
  dst.create(size, CV_8UC1);
  plan(src.size(), size);
  const kernels::LinearTaps taps{columns_.index.data(), columns_.weight.data(), size.width,
                                 block_start_.data(),   block_shuffle_.data(),  static_cast<int>(block_start_.size())};
  // Each output row reads two source rows' row passes; consecutive outputs share them.
  int held[2] = {-1, -1};
  for (int y = 0; y < size.height; ++y) {
    const int first = rows_.index[y];
    if (held[0] != first) {
      if (held[1] == first) {
        std::swap(lines_[0], lines_[1]);
        std::swap(held[0], held[1]);
      } else {
        kernels::linearRow(level, src.ptr<std::uint8_t>(first), taps, lines_[0].data());
        held[0] = first;
      }
    }
    if (held[1] != first + 1) {
      kernels::linearRow(level, src.ptr<std::uint8_t>(first + 1), taps, lines_[1].data());
      held[1] = first + 1;
    }
    kernels::linearColumn(level, lines_[0].data(), lines_[1].data(), rows_.weight[y], size.width,
                          dst.ptr<std::uint8_t>(y));
  }
}

}  // namespace enhanced_orb
