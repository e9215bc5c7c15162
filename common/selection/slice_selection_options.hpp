#pragma once

#include <string>

#include "common/sampling/sampling_pattern.hpp"
#include "common/search/search_strategy.hpp"
#include "common/selection/slice_score.hpp"

namespace kapfix {

// Settings of the Slice Selection Process (SPEC §2.6); defaults are the thesis's.
struct SliceSelectionOptions {
  int slice_count = 9;
  int patch_size = 100;  // [px] side of the square patch
  SamplingOptions sampling;
  SearchOptions search;        // what fixation will use: the graph must show its failures
  double hysteresis_px = 1.5;  // [px] for SliceScore::dc_hysteresis
  SliceScoreKind score = SliceScoreKind::kDc;
  int deadline_frames = 0;        // frames to consume at most; 0 = all (else ≥ 2: one sample)
  double deadline_seconds = 0.0;  // [s] stop consuming frames after this; 0 = no limit

  bool IsValid(std::string* error) const;
};

}  // namespace kapfix
