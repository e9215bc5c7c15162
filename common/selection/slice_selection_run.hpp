#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "common/sampling/sample_set.hpp"
#include "common/search/search_strategy.hpp"
#include "common/selection/slice_selection.hpp"
#include "common/selection/slice_selection_options.hpp"

namespace kapfix {

// The Slice Selection Process one frame at a time (SPEC §2.6), for a live free swing: the
// agent feeds each camera frame as it arrives and needs only the previous frame, not the whole
// swing, so memory stays at two frames whatever the deadline. SelectSlice runs the same steps
// over stored frames.
//
// options.deadline_frames / deadline_seconds are the caller's to enforce (it decides when to
// stop feeding); this class only measures and scores.
class SliceSelectionRun {
 public:
  // `first_plane`: the swing's first frame as a single-channel plane (see ExtractChannel). The
  // strategy must outlive the run. Throws std::invalid_argument for invalid options or a patch
  // that does not fit the frame.
  SliceSelectionRun(const cv::Mat& first_plane, const SearchStrategy& strategy,
                    const SliceSelectionOptions& options);

  // One graph sample per slice: `plane` against the previous frame. Throws
  // std::invalid_argument when its size or type differs from the first plane's.
  void AddFrame(const cv::Mat& plane);

  int frames_used() const { return frames_used_; }  // first frame included
  // Each slice's graph so far, in index order (1 … slice_count), [px] per sample.
  std::vector<std::vector<double>> Graphs() const;
  // Scores and ranking of what was measured so far; `deadline_hit` is copied into the result.
  SliceSelection Result(bool deadline_hit) const;

 private:
  const SearchStrategy& strategy_;
  SliceSelectionOptions options_;
  std::vector<SliceScore> slices_;
  std::vector<SampleSet> samples_;   // per slice measured; empty for twins
  std::vector<std::size_t> source_;  // slice whose graph stands for this one (clamped twins)
  cv::Mat previous_;
  int frames_used_ = 1;
};

}  // namespace kapfix
