#pragma once

#include <opencv2/core.hpp>

#include "common/search/search_strategy.hpp"

namespace kapfix::bench {

// cv::matchTemplate (TM_SQDIFF) of the reference patch's bounding box over the whole current
// frame: the exhaustive 2-D peer the targets are stated against.
class MatchTemplatePeer final : public SearchStrategy {
 public:
  std::string name() const override { return "cv::matchTemplate"; }
  SearchResult Search(const ReferencePatch& reference, const cv::Mat& current,
                      const SearchOptions& options) const override;
};

// cv::phaseCorrelate over whole frames with a Hann window. Debian's OpenCV 4.6 multiplies the
// window into its inputs in place when no padding is needed (SPEC §8), so the window is
// applied here on float copies and phaseCorrelate gets no window. The windowed reference is
// derived once per stored reference (ReferencePatch::Derived).
class PhaseCorrelatePeer final : public SearchStrategy {
 public:
  std::string name() const override { return "cv::phaseCorrelate"; }
  SearchResult Search(const ReferencePatch& reference, const cv::Mat& current,
                      const SearchOptions& options) const override;
};

}  // namespace kapfix::bench
