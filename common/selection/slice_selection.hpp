#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "common/search/search_strategy.hpp"
#include "common/selection/slice_score.hpp"
#include "common/selection/slice_selection_options.hpp"

namespace kapfix {

// What the Slice Selection Process found (SPEC §2.6): goes to the operator, who confirms the
// recommended slice or picks another.
struct SliceSelection {
  std::vector<SliceScore> slices;  // one per slice, in index order 1 … slice_count
  std::vector<int> ranking;        // slice indices, best first (RankSlices)
  int best_slice = 0;              // ranking.front()
  bool deadline_hit = false;       // stopped before the last frame
  int frames_used = 0;             // frames consumed; each graph has frames_used − 1 samples
};

// Runs SSP over the frames of a free swing (single-channel planes of equal size and type, see
// ExtractChannel): every slice's displacement graph (§2.4) with `strategy`, its DC counts and
// FFT score, and its single-shot score on planes[0].
//
// Frames are consumed one at a time for all slices together, so that at a deadline every
// slice has been measured over the same frames. The first pair is always measured (a
// deadline_seconds too short to allow anything still yields one sample per slice); the clock
// is checked before each later frame. progress(done, total) follows each frame pair, total =
// frame pairs allowed by deadline_frames. Slices whose patches coincide (outer slices clamped
// into the frame) are measured once.
//
// Throws std::invalid_argument for invalid options, fewer than two frames, mismatched planes
// or a patch that does not fit the frame.
SliceSelection SelectSlice(const std::vector<cv::Mat>& planes, const SearchStrategy& strategy,
                           const SliceSelectionOptions& options,
                           const std::function<void(int, int)>& progress = nullptr);

}  // namespace kapfix
