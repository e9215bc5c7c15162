#pragma once

#include "common/search/axis_probe.hpp"
#include "common/search/search_strategy.hpp"

namespace kapfix {

// Base of the strategies that search one axis at a time through an AxisProbe ("all" and
// the thesis's hierarchical presets): it runs the axes SearchOptions asks for, refines the
// sub-pixel part and reads the confidence off what the probe scored.
class AxisSearch : public SearchStrategy {
 public:
  SearchResult Search(const ReferencePatch& reference, const cv::Mat& current,
                      const SearchOptions& options) const final;

 protected:
  // Scores positions through `probe` (centred on probe.centre_position(), range `range`).
  // The answer is the lowest distance scored along the axis, whichever level scored it.
  virtual void SearchAxis(AxisProbe& probe, int range) const = 0;
};

}  // namespace kapfix
