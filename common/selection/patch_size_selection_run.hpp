#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "common/sampling/sample_set.hpp"
#include "common/search/search_strategy.hpp"
#include "common/selection/patch_size_selection.hpp"

namespace kapfix {

// Patch Size Selection one frame at a time (SPEC §2.5), for a live free swing: every candidate
// size is measured on each frame as it arrives, so only the previous frame is kept.
// SelectPatchSize runs the same steps over stored frames.
class PatchSizeSelectionRun {
 public:
  // Throws std::invalid_argument for invalid options or a size that does not fit the frame.
  // The strategy must outlive the run.
  PatchSizeSelectionRun(const cv::Mat& first_plane, const SearchStrategy& strategy,
                        PatchSizeSelectionOptions options);

  // One graph sample per candidate size. Throws std::invalid_argument when the plane's size or
  // type differs from the first plane's.
  void AddFrame(const cv::Mat& plane);

  int frames_used() const { return frames_used_; }  // first frame included
  // Each candidate's graph so far, in the order of options.sizes [px per sample].
  const std::vector<std::vector<double>>& graphs() const { return graphs_; }
  PatchSizeSelection Result() const;

 private:
  const SearchStrategy& strategy_;
  PatchSizeSelectionOptions options_;
  std::vector<SampleSet> samples_;
  std::vector<std::vector<double>> graphs_;
  cv::Mat previous_;
  int frames_used_ = 1;
};

}  // namespace kapfix
