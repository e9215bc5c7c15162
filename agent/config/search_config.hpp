#pragma once

#include <string>

#include "common/image/color_channel.hpp"
#include "common/sampling/sampling_pattern.hpp"
#include "common/search/search_strategy.hpp"

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
  ColorChannel channel = ColorChannel::kGreen;  // green or rgb
  bool subpixel = true;                         // parabola refinement

  bool IsValid(std::string* error) const;
};

}  // namespace kapfix::agent
