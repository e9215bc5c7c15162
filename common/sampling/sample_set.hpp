#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "common/sampling/sampling_pattern.hpp"

namespace kapfix {

// A horizontal run of sampled pixels in frame coordinates: x … x + length − 1 on row y.
struct SampleSpan {
  int y = 0;
  int x = 0;
  int length = 0;
};

// The sampled pixels of one or more patches in frame coordinates, arranged for the distance's
// hot loop: runs of at least kMinSpanLength neighbouring pixels become spans (contiguous
// memory, vectorised), the rest stay single points (a gather).
class SampleSet {
 public:
  static constexpr int kMinSpanLength = 8;

  SampleSet() = default;
  // Builds the set from the patches' rectangles, each sampled with `sampling` (the same
  // pattern, relative to each rectangle's top-left corner). Overlapping rectangles count a
  // pixel once.
  SampleSet(const std::vector<cv::Rect>& patches, const SamplingOptions& sampling);
  // Builds the set from explicit frame coordinates (deduplicated).
  explicit SampleSet(std::vector<cv::Point> points);

  const std::vector<SampleSpan>& spans() const { return spans_; }
  const std::vector<cv::Point>& singles() const { return singles_; }
  // Number of sampled pixels.
  int size() const { return size_; }
  bool empty() const { return size_ == 0; }
  // Smallest rectangle holding every sampled pixel.
  cv::Rect bounds() const { return bounds_; }
  // Every sampled pixel, spans first (in span order), then singles: the order in which the
  // reference values are stored.
  std::vector<cv::Point> Points() const;

 private:
  void Build(std::vector<cv::Point> points);

  std::vector<SampleSpan> spans_;
  std::vector<cv::Point> singles_;
  int size_ = 0;
  cv::Rect bounds_;
};

}  // namespace kapfix
