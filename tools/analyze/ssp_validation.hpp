#pragma once

#include <functional>
#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "common/analysis/spearman.hpp"
#include "common/selection/slice_selection.hpp"
#include "tools/analyze/swing_setup.hpp"

namespace kapfix::analyze {

// SSP checked against what it is for (issue 12): slices scored on one free swing (seed A),
// then every distinct slice fixated in closed loop (EvaluateClosedLoop: the simulated kite,
// servos, controller) on another swing (seed B), and each score's ranking compared with the
// fixation error's by Spearman with its p-value. Slices that share a patch (see SliceGroups)
// are one measurement and enter once, under their first index.
struct SspValidationSetup {
  SwingArgs swing;  // image, seed A, frame size, sampling; the strategy is fixed below
  std::string strategy = "pyr";
  SliceSelectionOptions selection;
  std::uint32_t validation_seed = 0;  // seed B; 0 = swing.seed + 1000
  int closed_loop_frames = 300;
};

struct SspValidation {
  SliceSelection selection;              // scores on seed A, every slice
  std::vector<std::vector<int>> groups;  // SliceGroups of the frame
  std::vector<int> distinct;             // first index of each group
  std::vector<double> fixation_rms_px;   // [px] closed-loop RMS view error per distinct slice
  // Per distinct slice, the scores in the orientation "higher = predicted worse" (DC, DC with
  // hysteresis, FFT as they are; single-shot negated), keyed dc, dc-hyst, fft, single-shot.
  std::map<std::string, std::vector<double>> predicted_badness;
  std::map<std::string, SpearmanResult> spearman;  // predicted badness vs fixation RMS
  int best_slice = 0;   // lowest DC among distinct slices (SSP's pick, seed A)
  int worst_slice = 0;  // highest DC among distinct slices
  double upscale = 1.0;
};

// Throws std::invalid_argument with the reason (sizes named) for a frame too small for the
// slices or patch, an unknown strategy, or invalid options.
SspValidation ValidateSsp(const SspValidationSetup& setup,
                          const std::function<void(const std::string&, int, int)>& progress);

}  // namespace kapfix::analyze
