#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string_view>
#include <vector>

#include "common/selection/displacement_graph.hpp"

namespace kapfix {

// Which score ranks the slices (SPEC §2.6). The thesis's is the DC count; the others are
// reported beside it so that `--validate` can tell which predicts fixation quality best.
enum class SliceScoreKind {
  kDc,            // "dc": direction changes, fewer is better
  kDcHysteresis,  // "dc-hyst": direction changes with hysteresis, fewer is better
  kFft,           // "fft": FFT score, lower is better
  kSingleShot,    // "single-shot": single-frame score, higher is better
};

std::optional<SliceScoreKind> ParseSliceScoreKind(std::string_view text);
std::string_view ToString(SliceScoreKind kind);

// Everything SSP measured for one slice, for the operator's panel.
struct SliceScore {
  int index = 0;   // 1 = top slice
  cv::Rect patch;  // [px] the slice's patch in the frame
  DisplacementGraph graph;
  int dc = 0;                // direction changes of the graph
  int dc_hysteresis = 0;     // direction changes with the options' hysteresis
  double fft = 0.0;          // [px] FftScore of the graph (not divided by 1000)
  double single_shot = 0.0;  // SingleShotScore::score on the first frame
  // SingleShotScore::ambiguous on the first frame: a rival valley nearly as good as the
  // self-match (a repetitive texture); such a slice can be locked one period off.
  bool ambiguous = false;
};

// Slice indices, best first (SPEC §2.6): unambiguous slices before ambiguous ones (issue 9:
// SSP steers away from a patch a neighbouring texture period could steal); then by `kind` (dc,
// dc-hyst and fft ascending, single-shot descending); ties by FFT score ascending; then by
// closeness to the frame's centre, i.e. to slice (slice_count + 1) / 2; then the upper slice, so
// that the order is total. slice_count = 0 takes the largest index among `scores` (right for a full
// set).
std::vector<int> RankSlices(const std::vector<SliceScore>& scores, SliceScoreKind kind,
                            int slice_count = 0);

}  // namespace kapfix
