#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

namespace kapfix {

class ReferencePatch;

// SSD of a dense rectangular 8-bit block at many positions of a current plane, computed
// exactly as Σr² − 2·Σr·c + Σc²: the cross term is a dot product of the block's rows, widened
// to 16 bits and zero-padded to whole vectors, so rows of any width (a coarse pyramid level's
// 25 pixels, a full patch's 100) run without a remainder loop; Σc² comes from running sums of
// squares shared by neighbouring positions. Integer arithmetic throughout: every score equals
// the direct SSD bit for bit, so a search built on it returns what the direct one would.
class SlidingSsd {
 public:
  SlidingSsd() = default;
  explicit SlidingSsd(const cv::Mat& block);  // CV_8UC1, non-empty

  // Built once per reference (ReferencePatch::Derived) when its sampled pixels fill their
  // bounding box (sampling "all") on an 8-bit plane; nullptr otherwise.
  static const SlidingSsd* ForReference(const ReferencePatch& reference);

  bool empty() const { return width_ == 0; }
  cv::Size size() const { return {width_, height_}; }

  // out[i] = SSD between the block and the block of `current` (CV_8UC1) whose top-left corner
  // is first + (i, 0) (along_x) or first + (0, i), for i < count. Every such block must lie
  // inside `current`.
  void Score(const cv::Mat& current, cv::Point first, int count, bool along_x,
             std::int64_t* out) const;
  // The SSD at the single position `at` (top-left corner), directly: cheaper than Score for
  // one position, which would pay for running sums it cannot share.
  std::int64_t At(const cv::Mat& current, cv::Point at) const;

 private:
  // How many of the block's rows from `c` on can be read padded inside current's buffer.
  int PaddedRows(const cv::Mat& current, const std::uint8_t* c) const;

  int width_ = 0;
  int height_ = 0;
  int padded_ = 0;                  // row length in rows_: width rounded up to whole vectors
  std::vector<std::int16_t> rows_;  // the block, widened and zero-padded
  std::vector<std::int16_t> mask_;  // one row: −1 (all ones) on the block, 0 on the padding
  std::int64_t sum_squares_ = 0;    // Σr²
};

}  // namespace kapfix
