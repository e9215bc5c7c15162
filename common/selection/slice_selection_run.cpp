#include "common/selection/slice_selection_run.hpp"

#include <stdexcept>
#include <string>

#include "common/selection/direction_changes.hpp"
#include "common/selection/displacement_graph.hpp"
#include "common/selection/fft_score.hpp"
#include "common/selection/single_shot_score.hpp"
#include "common/selection/slice_geometry.hpp"

namespace kapfix {

SliceSelectionRun::SliceSelectionRun(const cv::Mat& first_plane, const SearchStrategy& strategy,
                                     const SliceSelectionOptions& options)
    : strategy_(strategy), options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("SliceSelectionRun: " + error);
  CheckSwingPlanes({first_plane}, "SliceSelectionRun");
  const auto count = static_cast<std::size_t>(options_.slice_count);
  slices_.resize(count);
  samples_.resize(count);
  source_.resize(count);
  for (std::size_t i = 0; i < count; ++i) {
    SliceScore& slice = slices_[i];
    slice.index = static_cast<int>(i) + 1;
    slice.patch =
        SlicePatch(first_plane.size(), options_.slice_count, slice.index, options_.patch_size);
    source_[i] = i;
    // Outer slices clamped into the frame can coincide: measure such a patch once.
    for (std::size_t j = 0; j < i; ++j) {
      if (slices_[j].patch == slice.patch) {
        source_[i] = j;
        break;
      }
    }
    if (source_[i] == i) {
      samples_[i] = SampleSet({slice.patch}, options_.sampling);
      const SingleShotScore single_shot =
          ComputeSingleShotScore(first_plane, slice.patch, options_.sampling, options_.search);
      slice.single_shot = single_shot.score;
      slice.ambiguous = single_shot.ambiguous;
    }
  }
  previous_ = first_plane.clone();
}

void SliceSelectionRun::AddFrame(const cv::Mat& plane) {
  if (plane.size() != previous_.size() || plane.type() != previous_.type()) {
    throw std::invalid_argument("SliceSelectionRun: frame " + std::to_string(frames_used_) +
                                " differs in size or type from the first frame");
  }
  for (std::size_t i = 0; i < slices_.size(); ++i) {
    if (source_[i] != i) continue;
    slices_[i].graph.samples.push_back(
        MeasureDisplacement(previous_, plane, samples_[i], strategy_, options_.search));
  }
  plane.copyTo(previous_);
  ++frames_used_;
}

std::vector<std::vector<double>> SliceSelectionRun::Graphs() const {
  std::vector<std::vector<double>> graphs;
  graphs.reserve(slices_.size());
  for (std::size_t i = 0; i < slices_.size(); ++i) {
    graphs.push_back(slices_[source_[i]].graph.samples);
  }
  return graphs;
}

SliceSelection SliceSelectionRun::Result(bool deadline_hit) const {
  SliceSelection selection;
  selection.slices = slices_;
  for (std::size_t i = 0; i < selection.slices.size(); ++i) {
    SliceScore& slice = selection.slices[i];
    if (source_[i] != i) {
      const SliceScore& twin = selection.slices[source_[i]];
      slice.graph = twin.graph;
      slice.dc = twin.dc;
      slice.dc_hysteresis = twin.dc_hysteresis;
      slice.fft = twin.fft;
      slice.single_shot = twin.single_shot;
      slice.ambiguous = twin.ambiguous;
      continue;
    }
    slice.dc = CountDirectionChanges(slice.graph.samples);
    slice.dc_hysteresis = CountDirectionChanges(slice.graph.samples, options_.hysteresis_px);
    slice.fft = FftScore(slice.graph.samples);
  }
  selection.ranking = RankSlices(selection.slices, options_.score, options_.slice_count);
  selection.best_slice = selection.ranking.front();
  selection.deadline_hit = deadline_hit;
  selection.frames_used = frames_used_;
  return selection;
}

}  // namespace kapfix
