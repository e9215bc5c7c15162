#include "common/sampling/sample_set.hpp"

#include <algorithm>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace kapfix {

SampleSet::SampleSet(const std::vector<cv::Rect>& patches, const SamplingOptions& sampling) {
  std::vector<cv::Point> points;
  for (const cv::Rect& patch : patches) {
    for (const cv::Point& offset : MakeSamplingPattern(patch.size(), sampling)) {
      points.push_back(patch.tl() + offset);
    }
  }
  Build(std::move(points));
}

SampleSet::SampleSet(std::vector<cv::Point> points) { Build(std::move(points)); }

void SampleSet::Build(std::vector<cv::Point> points) {
  std::sort(points.begin(), points.end(), [](const cv::Point& a, const cv::Point& b) {
    return a.y != b.y ? a.y < b.y : a.x < b.x;
  });
  points.erase(std::unique(points.begin(), points.end()), points.end());
  size_ = static_cast<int>(points.size());
  if (points.empty()) return;
  bounds_ = cv::boundingRect(points);
  for (std::size_t i = 0; i < points.size();) {
    std::size_t j = i + 1;
    while (j < points.size() && points[j].y == points[i].y && points[j].x == points[j - 1].x + 1) {
      ++j;
    }
    const int run = static_cast<int>(j - i);
    if (run >= kMinSpanLength) {
      spans_.push_back({points[i].y, points[i].x, run});
    } else {
      singles_.insert(singles_.end(), points.begin() + static_cast<std::ptrdiff_t>(i),
                      points.begin() + static_cast<std::ptrdiff_t>(j));
    }
    i = j;
  }
}

std::vector<cv::Point> SampleSet::Points() const {
  std::vector<cv::Point> points;
  points.reserve(static_cast<std::size_t>(size_));
  for (const SampleSpan& span : spans_) {
    for (int k = 0; k < span.length; ++k) points.emplace_back(span.x + k, span.y);
  }
  points.insert(points.end(), singles_.begin(), singles_.end());
  return points;
}

}  // namespace kapfix
