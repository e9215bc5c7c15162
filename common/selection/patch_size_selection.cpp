#include "common/selection/patch_size_selection.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "common/selection/direction_changes.hpp"
#include "common/selection/displacement_graph.hpp"
#include "common/selection/fft_score.hpp"
#include "common/selection/slice_geometry.hpp"

namespace kapfix {
namespace {

// [px] the thesis's default patch size, preferred when the scores cannot tell sizes apart.
constexpr int kPreferredSizePx = 100;

}  // namespace

bool PatchSizeSelectionOptions::IsValid(std::string* error) const {
  if (sizes.empty()) {
    if (error) *error = "no candidate patch sizes";
    return false;
  }
  for (const int size : sizes) {
    if (size < 1) {
      if (error) *error = "patch sizes must be ≥ 1 px, got " + std::to_string(size);
      return false;
    }
  }
  return sampling.IsValid(error) && search.IsValid(error);
}

int BestPatchSize(const std::vector<PatchSizeScore>& scores) {
  const auto best = std::min_element(scores.begin(), scores.end(),
                                     [](const PatchSizeScore& a, const PatchSizeScore& b) {
                                       if (a.dc != b.dc) return a.dc < b.dc;
                                       if (a.fft != b.fft) return a.fft < b.fft;
                                       const int da = std::abs(a.size - kPreferredSizePx);
                                       const int db = std::abs(b.size - kPreferredSizePx);
                                       if (da != db) return da < db;
                                       return a.size < b.size;
                                     });
  return best == scores.end() ? 0 : best->size;
}

PatchSizeSelection SelectPatchSize(const std::vector<cv::Mat>& planes,
                                   const SearchStrategy& strategy,
                                   const PatchSizeSelectionOptions& options,
                                   const std::function<void(int, int)>& progress) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("SelectPatchSize: " + error);
  if (planes.size() < 2) {
    throw std::invalid_argument("SelectPatchSize: needs at least two frames, got " +
                                std::to_string(planes.size()));
  }
  CheckSwingPlanes(planes, "SelectPatchSize");
  const cv::Size frame = planes.front().size();
  // Check every size before the long part, so that a bad one fails at once.
  std::vector<cv::Rect> patches;
  for (const int size : options.sizes) patches.push_back(SlicePatch(frame, 1, 1, size));

  const int pairs = static_cast<int>(planes.size()) - 1;
  const int total = pairs * static_cast<int>(options.sizes.size());
  PatchSizeSelection selection;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const int done_before = static_cast<int>(i) * pairs;
    std::function<void(int, int)> step;
    if (progress) step = [&](int done, int) { progress(done_before + done, total); };
    const DisplacementGraph graph = BuildDisplacementGraph(planes, patches[i], options.sampling,
                                                           strategy, options.search, step);
    selection.sizes.push_back(
        {options.sizes[i], CountDirectionChanges(graph.samples), FftScore(graph.samples)});
  }
  selection.best_size = BestPatchSize(selection.sizes);
  return selection;
}

}  // namespace kapfix
