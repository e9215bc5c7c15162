#include "common/selection/patch_size_selection.hpp"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>

#include "common/selection/displacement_graph.hpp"
#include "common/selection/patch_size_selection_run.hpp"

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
  PatchSizeSelectionRun run(planes.front(), strategy, options);
  const int sizes = static_cast<int>(options.sizes.size());
  const int total = (static_cast<int>(planes.size()) - 1) * sizes;
  for (std::size_t t = 1; t < planes.size(); ++t) {
    run.AddFrame(planes[t]);
    if (progress) progress(static_cast<int>(t) * sizes, total);
  }
  return run.Result();
}

}  // namespace kapfix
