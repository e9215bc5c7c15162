#include "common/selection/patch_size_selection_run.hpp"

#include <stdexcept>
#include <string>

#include "common/selection/direction_changes.hpp"
#include "common/selection/displacement_graph.hpp"
#include "common/selection/fft_score.hpp"
#include "common/selection/slice_geometry.hpp"

namespace kapfix {

PatchSizeSelectionRun::PatchSizeSelectionRun(const cv::Mat& first_plane,
                                             const SearchStrategy& strategy,
                                             PatchSizeSelectionOptions options)
    : strategy_(strategy), options_(std::move(options)) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("PatchSizeSelectionRun: " + error);
  CheckSwingPlanes({first_plane}, "PatchSizeSelectionRun");
  // Every size is checked here, before the swing, so that a bad one fails at once.
  for (const int size : options_.sizes) {
    samples_.emplace_back(std::vector<cv::Rect>{SlicePatch(first_plane.size(), 1, 1, size)},
                          options_.sampling);
  }
  graphs_.resize(options_.sizes.size());
  previous_ = first_plane.clone();
}

void PatchSizeSelectionRun::AddFrame(const cv::Mat& plane) {
  if (plane.size() != previous_.size() || plane.type() != previous_.type()) {
    throw std::invalid_argument("PatchSizeSelectionRun: frame " + std::to_string(frames_used_) +
                                " differs in size or type from the first frame");
  }
  for (std::size_t i = 0; i < samples_.size(); ++i) {
    graphs_[i].push_back(
        MeasureDisplacement(previous_, plane, samples_[i], strategy_, options_.search));
  }
  plane.copyTo(previous_);
  ++frames_used_;
}

PatchSizeSelection PatchSizeSelectionRun::Result() const {
  PatchSizeSelection selection;
  for (std::size_t i = 0; i < graphs_.size(); ++i) {
    selection.sizes.push_back(
        {options_.sizes[i], CountDirectionChanges(graphs_[i]), FftScore(graphs_[i])});
  }
  selection.best_size = BestPatchSize(selection.sizes);
  return selection;
}

}  // namespace kapfix
