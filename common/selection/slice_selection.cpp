#include "common/selection/slice_selection.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "common/sampling/sample_set.hpp"
#include "common/selection/direction_changes.hpp"
#include "common/selection/fft_score.hpp"
#include "common/selection/single_shot_score.hpp"
#include "common/selection/slice_geometry.hpp"

namespace kapfix {

SliceSelection SelectSlice(const std::vector<cv::Mat>& planes, const SearchStrategy& strategy,
                           const SliceSelectionOptions& options,
                           const std::function<void(int, int)>& progress) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("SelectSlice: " + error);
  if (planes.size() < 2) {
    throw std::invalid_argument("SelectSlice: needs at least two frames, got " +
                                std::to_string(planes.size()));
  }
  CheckSwingPlanes(planes, "SelectSlice");

  const int count = options.slice_count;
  SliceSelection selection;
  selection.slices.resize(static_cast<std::size_t>(count));
  std::vector<SampleSet> samples(static_cast<std::size_t>(count));
  std::vector<int> source(static_cast<std::size_t>(count));  // slice measured in its stead
  for (int i = 0; i < count; ++i) {
    SliceScore& slice = selection.slices[static_cast<std::size_t>(i)];
    slice.index = i + 1;
    slice.patch = SlicePatch(planes.front().size(), count, i + 1, options.patch_size);
    source[static_cast<std::size_t>(i)] = i;
    for (int j = 0; j < i; ++j) {
      if (selection.slices[static_cast<std::size_t>(j)].patch == slice.patch) {
        source[static_cast<std::size_t>(i)] = j;
        break;
      }
    }
    if (source[static_cast<std::size_t>(i)] == i) {
      samples[static_cast<std::size_t>(i)] = SampleSet({slice.patch}, options.sampling);
    }
  }

  int limit = static_cast<int>(planes.size());
  if (options.deadline_frames > 0) limit = std::min(limit, options.deadline_frames);
  const auto start = std::chrono::steady_clock::now();
  selection.frames_used = 1;
  for (int t = 1; t < limit; ++t) {
    if (t > 1 && options.deadline_seconds > 0.0) {
      const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
      if (elapsed.count() >= options.deadline_seconds) break;
    }
    for (int i = 0; i < count; ++i) {
      if (source[static_cast<std::size_t>(i)] != i) continue;
      selection.slices[static_cast<std::size_t>(i)].graph.samples.push_back(
          MeasureDisplacement(planes[t - 1], planes[t], samples[static_cast<std::size_t>(i)],
                              strategy, options.search));
    }
    selection.frames_used = t + 1;
    if (progress) progress(t, limit - 1);
  }
  selection.deadline_hit = selection.frames_used < static_cast<int>(planes.size());

  for (int i = 0; i < count; ++i) {
    SliceScore& slice = selection.slices[static_cast<std::size_t>(i)];
    const int from = source[static_cast<std::size_t>(i)];
    if (from != i) {
      const SliceScore& twin = selection.slices[static_cast<std::size_t>(from)];
      slice.graph = twin.graph;
      slice.dc = twin.dc;
      slice.dc_hysteresis = twin.dc_hysteresis;
      slice.fft = twin.fft;
      slice.single_shot = twin.single_shot;
      continue;
    }
    slice.dc = CountDirectionChanges(slice.graph.samples);
    slice.dc_hysteresis = CountDirectionChanges(slice.graph.samples, options.hysteresis_px);
    slice.fft = FftScore(slice.graph.samples);
    slice.single_shot =
        ComputeSingleShotScore(planes.front(), slice.patch, options.sampling, options.search).score;
  }
  selection.ranking = RankSlices(selection.slices, options.score, count);
  selection.best_slice = selection.ranking.front();
  return selection;
}

}  // namespace kapfix
