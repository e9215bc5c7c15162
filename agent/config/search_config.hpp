#pragma once

#include <string>

#include "common/image/color_channel.hpp"
#include "common/sampling/sampling_pattern.hpp"
#include "common/search/search_strategy.hpp"
#include "common/selection/slice_score.hpp"

namespace kapfix::agent {

// The "search" section: how the matcher looks for the reference patch (SPEC §2.1–§2.3, §2.6).
// Defaults: resources/README.md.
struct SearchConfig {
  std::string strategy = "pyr";      // all, h23, h21, h19, h17, h15 or pyr
  SamplingOptions sampling;          // "all", "static", "random" or "random:F" (default random:0.1)
  int patch_px = 100;                // [px] side of the square patch
  int slices = 9;                    // horizontal bands for SSP
  SearchAxis axis = SearchAxis::kX;  // x (kite), y (boat) or both
  int range_px = 100;                // [px] R: shifts searched in [−R, R]
  ColorChannel channel = ColorChannel::kGreen;       // green or rgb-sum
  bool subpixel = true;                              // parabola refinement
  SliceScoreKind slice_score = SliceScoreKind::kDc;  // what ranks the slices in SSP
  double dc_hysteresis_px = 1.5;                     // [px] of the dc-hyst score
  // Free-swing processes (SSP, PSS, recording) stop after this many frames or seconds.
  int swing_frames = 300;     // [frames] 2…100000
  double swing_seconds = 20;  // [s] 0.1…3600

  bool IsValid(std::string* error) const;
};

}  // namespace kapfix::agent
