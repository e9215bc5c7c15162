#include "common/matching/sliding_ssd.hpp"

#include <algorithm>
#include <any>
#include <stdexcept>

#include "common/matching/reference_patch.hpp"
#include "common/matching/ssd_kernel.hpp"

namespace kapfix {
namespace {

constexpr int kVector = 16;  // [pixels] 16-bit lanes of one AVX2 register

}  // namespace

SlidingSsd::SlidingSsd(const cv::Mat& block)
    : width_(block.cols),
      height_(block.rows),
      padded_((block.cols + kVector - 1) / kVector * kVector) {
  if (block.type() != CV_8UC1 || block.empty()) {
    throw std::invalid_argument("SlidingSsd: expected a non-empty CV_8UC1 block");
  }
  rows_.assign(static_cast<std::size_t>(padded_) * static_cast<std::size_t>(height_), 0);
  mask_.assign(static_cast<std::size_t>(padded_), 0);
  std::fill_n(mask_.begin(), width_, static_cast<std::int16_t>(-1));
  for (int y = 0; y < height_; ++y) {
    const std::uint8_t* row = block.ptr<std::uint8_t>(y);
    std::int16_t* out = rows_.data() + static_cast<std::ptrdiff_t>(y) * padded_;
    for (int x = 0; x < width_; ++x) out[x] = row[x];
    sum_squares_ += SumSquares(row, width_);
  }
}

const SlidingSsd* SlidingSsd::ForReference(const ReferencePatch& reference) {
  if (reference.type() != CV_8UC1) return nullptr;
  const cv::Rect bounds = reference.samples().bounds();
  if (reference.size() != bounds.area() || !reference.samples().singles().empty()) return nullptr;
  const std::any& derived = reference.Derived(
      "sliding-ssd", [&]() -> std::any { return SlidingSsd(reference.image()(bounds)); });
  return std::any_cast<SlidingSsd>(&derived);
}

int SlidingSsd::PaddedRows(const cv::Mat& current, const std::uint8_t* c) const {
  // The padded rows read up to padded_ − width_ pixels past the block: harmless inside the
  // plane's buffer (they meet zeros), so only rows whose read would pass the buffer's end (the
  // last rows of the plane, at its right edge) take an exact-width loop.
  const std::size_t step = current.step1();
  int rows = height_;
  while (rows > 0 && c + (rows - 1) * step + padded_ > current.dataend) --rows;
  return rows;
}

std::int64_t SlidingSsd::At(const cv::Mat& current, cv::Point at) const {
  CV_Assert(current.type() == CV_8UC1 && !empty() &&
            (cv::Rect(at, size()) & cv::Rect(0, 0, current.cols, current.rows)) ==
                cv::Rect(at, size()));
  const std::size_t step = current.step1();
  const std::uint8_t* c = current.ptr<std::uint8_t>(at.y) + at.x;
  const int padded_rows = PaddedRows(current, c);
  std::int64_t sum = SsdRowsMasked(rows_.data(), mask_.data(), padded_, padded_rows, c, step);
  for (int y = padded_rows; y < height_; ++y) {
    const std::int16_t* r = rows_.data() + static_cast<std::ptrdiff_t>(y) * padded_;
    const std::uint8_t* cy = c + y * step;
    for (int x = 0; x < width_; ++x) {
      const std::int64_t d = r[x] - static_cast<std::int64_t>(cy[x]);
      sum += d * d;
    }
  }
  return sum;
}

void SlidingSsd::Score(const cv::Mat& current, cv::Point first, int count, bool along_x,
                       std::int64_t* out) const {
  if (count == 1) {
    out[0] = At(current, first);
    return;
  }
  const cv::Point last = first + (along_x ? cv::Point(count - 1, 0) : cv::Point(0, count - 1));
  const cv::Rect region(first.x, first.y, last.x - first.x + width_, last.y - first.y + height_);
  CV_Assert(current.type() == CV_8UC1 && count > 0 && !empty() &&
            (region & cv::Rect(0, 0, current.cols, current.rows)) == region);

  // Σc² at each position: sums of squares per column (along x) or per row (along y) over the
  // block's extent, then a window sliding over them.
  thread_local std::vector<std::int32_t> column_squares;
  thread_local std::vector<std::int64_t> row_squares;
  std::int64_t window = 0;
  if (along_x) {
    column_squares.assign(static_cast<std::size_t>(region.width), 0);
    for (int y = 0; y < height_; ++y) {
      AddSquares(current.ptr<std::uint8_t>(first.y + y) + first.x, region.width,
                 column_squares.data());
    }
    for (int x = 0; x < width_; ++x) window += column_squares[x];
    for (int i = 0; i < count; ++i) {
      if (i > 0) window += column_squares[i + width_ - 1] - column_squares[i - 1];
      out[i] = sum_squares_ + window;
    }
  } else {
    row_squares.resize(static_cast<std::size_t>(region.height));
    for (int y = 0; y < region.height; ++y) {
      row_squares[y] = SumSquares(current.ptr<std::uint8_t>(first.y + y) + first.x, width_);
    }
    for (int y = 0; y < height_; ++y) window += row_squares[y];
    for (int i = 0; i < count; ++i) {
      if (i > 0) window += row_squares[i + height_ - 1] - row_squares[i - 1];
      out[i] = sum_squares_ + window;
    }
  }

  // −2Σr·c.
  const std::size_t step = current.step1();
  for (int i = 0; i < count; ++i) {
    const cv::Point at = along_x ? first + cv::Point(i, 0) : first + cv::Point(0, i);
    const std::uint8_t* c = current.ptr<std::uint8_t>(at.y) + at.x;
    const int safe = PaddedRows(current, c);
    std::int64_t dot = DotRows(rows_.data(), padded_, safe, c, step);
    for (int y = safe; y < height_; ++y) {
      const std::int16_t* r = rows_.data() + static_cast<std::ptrdiff_t>(y) * padded_;
      const std::uint8_t* cy = c + y * step;
      for (int x = 0; x < width_; ++x) dot += static_cast<std::int64_t>(r[x]) * cy[x];
    }
    out[i] -= 2 * dot;
  }
}

}  // namespace kapfix
