#include "common/evaluation/free_swing_slice.hpp"

#include <optional>
#include <stdexcept>
#include <string>

#include "common/image/color_channel.hpp"
#include "common/selection/slice_selection_run.hpp"

namespace kapfix {

int FreeSwingSlice(SimulatedPlatform& platform, const FixationOptions& fixation,
                   const SearchStrategy& strategy, int frames) {
  return FreeSwingRanking(platform, fixation, strategy, frames).front();
}

SliceSelectionOptions SliceSelectionOptionsFor(const FixationOptions& fixation) {
  SliceSelectionOptions options;
  options.slice_count = fixation.slice_count;
  options.patch_size = fixation.patch_size;
  options.sampling = fixation.sampling;
  options.search = fixation.search;
  return options;
}

std::vector<int> FreeSwingRanking(SimulatedPlatform& platform, const FixationOptions& fixation,
                                  const SearchStrategy& strategy, int frames) {
  if (frames < 2) {
    throw std::invalid_argument("free swing needs ≥ 2 frames, got " + std::to_string(frames));
  }
  const SliceSelectionOptions options = SliceSelectionOptionsFor(fixation);
  std::optional<SliceSelectionRun> run;
  for (int k = 0; k < frames; ++k) {
    if (k > 0) platform.Step();
    if (platform.FrameDropped(platform.frame())) continue;
    const cv::Mat plane = ExtractChannel(platform.Capture(), fixation.channel);
    if (run) {
      run->AddFrame(plane);
    } else {
      run.emplace(plane, strategy, options);
    }
  }
  if (!run || run->frames_used() < 2) {
    throw std::invalid_argument("free swing: fewer than 2 frames reached the camera");
  }
  return run->Result(/*deadline_hit=*/false).ranking;
}

}  // namespace kapfix
