#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "common/image/color_channel.hpp"
#include "common/sampling/sampling_pattern.hpp"
#include "common/search/search_strategy.hpp"
#include "common/selection/slice_score.hpp"

namespace kapfix::agent {

// The "search" section: how the matcher looks for the reference patch (SPEC §2.1–§2.3, §2.6).
// Defaults: resources/README.md.
struct SearchConfig {
  std::string strategy = "pyr";  // all, h23, h21, h19, h17, h15 or pyr
  SamplingOptions sampling;      // "all", "static", "random" or "random:F" (default random:0.1)
  int patch_px = 100;            // [px] side of the square patch
  int slices = 9;                // horizontal bands for SSP
  // x (the thesis's kite), y (a boat) or both. Both by default: a kite's view moves in Y too,
  // and an X-only loop leaves it there (realistic world, 13.4 px against 10.2 with
  // resources/kite.json; the cost is the sum of two 1-D searches).
  SearchAxis axis = SearchAxis::kBoth;
  int range_px = 100;                           // [px] R: shifts searched in [−R, R]
  ColorChannel channel = ColorChannel::kGreen;  // green or rgb-sum
  bool subpixel = true;                         // parabola refinement
  SliceScoreKind score = SliceScoreKind::kDc;   // what ranks the slices in SSP
  double hysteresis_px = 1.5;                   // [px] of the dc-hyst score
  // Free-swing processes (SSP, PSS, recording) stop after this many frames or seconds.
  int swing_frames = 300;     // [frames] 2…100000
  double swing_seconds = 20;  // [s] 0.1…3600
  // [s] a lock lost this long runs SSP over the free swing that follows and moves the fixation
  // to its slice, on the same reference frame (SPEC §2.6); 0 = never.
  double ssp_after_lost_s = 3;

  bool IsValid(std::string* error) const;

  // The operator-set members by the names of their settings (kapfix.v1.SearchSettings), listed
  // once: the state, a command's merge and the range check see them as that message
  // (SettingsFromOptions, CopySettings).
  template <typename Visitor>
  void VisitFields(Visitor&& visit) {
    visit("strategy", strategy);
    visit("sampling", sampling.kind, SamplingKindOfWord);
    visit("random_fraction", sampling.fraction);
    visit("patch_size_px", patch_px);
    visit("slice_count", slices);
    visit("axis", axis, ParseSearchAxis);
    visit("search_range_px", range_px);
    visit("subpixel", subpixel);
    visit("channel", channel, ParseColorChannel);
    visit("slice_score", score, SliceScoreOfWord);
    visit("dc_hysteresis_px", hysteresis_px);
    visit("ssp_after_lost_s", ssp_after_lost_s);
  }

 private:
  // The setting words of kapfix.v1.Sampling and SliceScoreKind ("random", "dc_hysteresis")
  // as common/'s enums.
  static std::optional<SamplingKind> SamplingKindOfWord(std::string_view word);
  static std::optional<SliceScoreKind> SliceScoreOfWord(std::string_view word);
};

}  // namespace kapfix::agent
