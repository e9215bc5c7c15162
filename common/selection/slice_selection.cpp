#include "common/selection/slice_selection.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <string>

#include "common/selection/displacement_graph.hpp"
#include "common/selection/slice_selection_run.hpp"

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

  SliceSelectionRun run(planes.front(), strategy, options);
  int limit = static_cast<int>(planes.size());
  if (options.deadline_frames > 0) limit = std::min(limit, options.deadline_frames);
  const auto start = std::chrono::steady_clock::now();
  for (int t = 1; t < limit; ++t) {
    // The first pair is always measured, so that even a tiny deadline yields one sample.
    if (t > 1 && options.deadline_seconds > 0.0) {
      const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
      if (elapsed.count() >= options.deadline_seconds) break;
    }
    run.AddFrame(planes[static_cast<std::size_t>(t)]);
    if (progress) progress(t, limit - 1);
  }
  return run.Result(run.frames_used() < static_cast<int>(planes.size()));
}

}  // namespace kapfix
