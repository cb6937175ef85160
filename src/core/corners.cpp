#include "enhanced_orb/corners.h"

#include <algorithm>
#include <cstring>

#include "enhanced_orb/adaptive_threshold.h"
#include "enhanced_orb/simd.h"
#include "kernels/fast_score.h"
#include "kernels/suppression.h"

namespace enhanced_orb {
namespace {

// The non-maximum suppression of detectCorners on one band of cells (one grid row), a whole
// interior row at a time. b (a corner's score, 0 for other pixels) is computed with each pixel's
// own cell threshold; a neighbour across a cell edge counts 0.
class BandSuppression {
public:
  // starts[0..cells]: the first column of each cell of the band and, last, the end of the interior.
  BandSuppression(const cv::Mat& scores, const int* starts, int cells, const int* thresholds,
                  std::vector<std::uint8_t>& buffer)
      : scores_(scores), x0_(starts[0]), cells_(cells), simd_(activeSimdLevel()) {
    width_ = starts[cells] - x0_;
    for (int c = 0; c <= cells; ++c) {
      starts_[c] = starts[c] - x0_;
    }
    for (int c = 0; c < cells; ++c) {
      thresholds_[c] = static_cast<std::uint8_t>(thresholds[c]);
    }
    const size_t row = static_cast<size_t>(width_) + 72;  // a zero column each side, 64-flag reads
    buffer.assign(7 * row, 0);
    for (int k = 0; k < 3; ++k) {
      b_[k] = buffer.data() + k * row + 1;
      around_[k] = buffer.data() + (3 + k) * row + 1;
    }
    keep_ = buffer.data() + 6 * row;
  }

  // Appends the corners of rows [y0, y1) of the band to each cell's list.
  void run(int y0, int y1, std::vector<std::vector<cv::KeyPoint>>& cell_corners) {
    clearRow(0);
    fillRow(y0, 1);
    for (int y = y0; y < y1; ++y) {
      if (y + 1 < y1) {
        fillRow(y + 1, 2);
      } else {
        clearRow(2);
      }
      const std::uint8_t* here = b_[1];
      kernels::suppressionKeep(simd_, here, around_[0], around_[2], starts_, cells_, keep_);
      // Few flags are set: gather them 64 at a time into a bit mask and visit its set bits.
      int cell = 0;
      for (int i = 0; i < width_; i += 64) {
        std::uint64_t mask = 0;
        for (int w = 0; w < 8; ++w) {
          std::uint64_t flags;  // eight 0/1 bytes (the buffer's tail is zero)
          std::memcpy(&flags, keep_ + i + 8 * w, sizeof flags);
          mask |= ((flags * 0x0102040810204080ULL) >> 56) << (8 * w);
        }
        while (mask != 0) {
          const int j = i + __builtin_ctzll(mask);
          mask &= mask - 1;
          while (j >= starts_[cell + 1]) {
            ++cell;
          }
          cell_corners[cell].emplace_back(static_cast<float>(x0_ + j), static_cast<float>(y), 7.0f, -1.0f,
                                          static_cast<float>(here[j]));
        }
      }
      std::rotate(b_, b_ + 1, b_ + 3);
      std::rotate(around_, around_ + 1, around_ + 3);
    }
  }

private:
  void clearRow(int slot) {
    std::memset(b_[slot] - 1, 0, width_ + 2);
    std::memset(around_[slot] - 1, 0, width_ + 2);
  }

  // Slot `slot` gets row y's b and the maximum of each b's three horizontal neighbours in its cell.
  void fillRow(int y, int slot) {
    kernels::suppressionRow(simd_, scores_.ptr<std::uint8_t>(y) + x0_, starts_, thresholds_, cells_, b_[slot],
                            around_[slot]);
  }

  const cv::Mat& scores_;
  int x0_;
  int cells_;
  SimdLevel simd_;
  int width_ = 0;
  int starts_[33];
  std::uint8_t thresholds_[32];
  std::uint8_t* b_[3];
  std::uint8_t* around_[3];
  std::uint8_t* keep_;
};

// A band of cells (one grid row): its non-empty cells, left to right, as the suppression takes them.
struct Band {
  int cells = 0;
  int starts[33];      // each cell's first column and, last, the band's end
  int thresholds[32];  // each cell's threshold, clamped to [0, 255] as cv::FAST clamps it
  cv::Rect rows;       // the band's rows (and its last cell's columns)
};

// Grid row cy of `thresholds` inside `interior`; writes each pixel's threshold of the band's
// interior columns to `floors`. gridCell's cells tile the level.
Band bandOf(cv::Size size, const cv::Mat& thresholds, int cy, const cv::Rect& interior, std::uint8_t* floors) {
  Band band;
  for (int cx = 0; cx < thresholds.cols; ++cx) {
    const cv::Rect cell = gridCell(size, thresholds.rows, cx, cy) & interior;
    if (!cell.empty()) {
      band.starts[band.cells] = cell.x;
      band.thresholds[band.cells] = std::clamp(thresholds.at<int>(cy, cx), 0, 255);
      std::fill(floors + (cell.x - interior.x), floors + (cell.br().x - interior.x),
                static_cast<std::uint8_t>(band.thresholds[band.cells]));
      ++band.cells;
      band.rows = cell;
    }
  }
  if (band.cells > 0) {
    band.starts[band.cells] = band.rows.br().x;
  }
  return band;
}

}  // namespace

void detectCorners(const cv::Mat& level, const cv::Mat& thresholds, CornerWorkspace& ws,
                   std::vector<cv::KeyPoint>& corners) {
  CV_Assert(level.type() == CV_8UC1 && thresholds.type() == CV_32S && thresholds.rows == thresholds.cols);
  corners.clear();
  const cv::Rect interior(kEdgeThreshold, kEdgeThreshold, level.cols - 2 * kEdgeThreshold,
                          level.rows - 2 * kEdgeThreshold);
  if (interior.width <= 0 || interior.height <= 0) {
    return;
  }
  const kernels::FastScoreRowKernel score_row = kernels::fastScoreRowKernel(activeSimdLevel());
  ws.scores.create(level.size(), CV_8UC1);
  ws.floors.resize(static_cast<size_t>(interior.width));
  ws.cell_lists.resize(static_cast<size_t>(thresholds.rows));
  for (int cy = 0; cy < thresholds.rows; ++cy) {
    const Band band = bandOf(level.size(), thresholds, cy, interior, ws.floors.data());
    if (band.cells == 0) {
      continue;
    }
    // The band's FAST scores (only the interior of the map is written). A pixel scoring at or
    // below its cell's threshold can neither be a corner nor weigh in the suppression (which counts
    // neighbours of the same cell only), so the kernel may write 0 for it, and skip a vector of
    // such pixels.
    for (int y = band.rows.y; y < band.rows.br().y; ++y) {
      score_row(level.ptr<std::uint8_t>(y) + interior.x, static_cast<std::ptrdiff_t>(level.step), interior.width,
                ws.scores.ptr<std::uint8_t>(y) + interior.x, ws.floors.data());
    }
    // cv::FAST run on each cell's window (the cell widened by 3, where its circle reads) keeps a
    // corner when its score exceeds that of each of its 8 neighbours, a neighbour counting 0 unless
    // it lies in the cell and is a corner at the cell's threshold. With b = score for the cell's
    // corners and 0 elsewhere (in and around the cell), that is b above the largest b around it;
    // the band's rows are all it reads. Corners come cell by cell (row-major), each cell row by row.
    for (auto& list : ws.cell_lists) {
      list.clear();
    }
    BandSuppression(ws.scores, band.starts, band.cells, band.thresholds, ws.rows)
        .run(band.rows.y, band.rows.br().y, ws.cell_lists);
    for (int c = 0; c < band.cells; ++c) {
      corners.insert(corners.end(), ws.cell_lists[c].begin(), ws.cell_lists[c].end());
    }
  }
}

std::vector<cv::KeyPoint> detectCorners(const cv::Mat& level, const cv::Mat& thresholds) {
  CornerWorkspace ws;
  std::vector<cv::KeyPoint> corners;
  detectCorners(level, thresholds, ws, corners);
  return corners;
}

}  // namespace enhanced_orb
