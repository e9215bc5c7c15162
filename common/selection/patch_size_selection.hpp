#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "common/sampling/sampling_pattern.hpp"
#include "common/search/search_strategy.hpp"

namespace kapfix {

// Patch Size Selection (SPEC §2.5): the displacement graph of a patch centred in the frame
// (the central slice) for each candidate size; the size with the fewest DCs wins.

struct PatchSizeScore {
  int size = 0;      // [px] side of the square patch
  int dc = 0;        // direction changes of its displacement graph
  double fft = 0.0;  // [px] FftScore of the graph
};

struct PatchSizeSelection {
  std::vector<PatchSizeScore> sizes;  // in the order of the candidates
  int best_size = 0;                  // [px]
};

struct PatchSizeSelectionOptions {
  std::vector<int> sizes{50, 100, 150};  // [px] the thesis's candidates
  SamplingOptions sampling;
  SearchOptions search;

  bool IsValid(std::string* error) const;
};

// The winning size: fewest DCs; ties by the lower FFT score (steadier graph); then the size
// closest to 100 px, the thesis's tried default; then the smaller (cheaper) size. 0 if empty.
int BestPatchSize(const std::vector<PatchSizeScore>& scores);

// Runs PSS over the frames of a free swing (single-channel planes of equal size and type).
// progress(done, total) follows each frame, all sizes measured on it: done counts graph samples,
// total = sizes × (frames − 1).
// Throws std::invalid_argument for invalid options, fewer than two frames, mismatched planes
// or a size that does not fit the frame.
PatchSizeSelection SelectPatchSize(const std::vector<cv::Mat>& planes,
                                   const SearchStrategy& strategy,
                                   const PatchSizeSelectionOptions& options,
                                   const std::function<void(int, int)>& progress = nullptr);

}  // namespace kapfix
