#include "common/fixation/patch_self_confidence.hpp"

#include <stdexcept>
#include <string>

#include "common/image/color_channel.hpp"
#include "common/matching/reference_patch.hpp"
#include "common/sampling/sample_set.hpp"
#include "common/selection/slice_geometry.hpp"

namespace kapfix {

double PatchSelfConfidence(const cv::Mat& frame_bgr, int slice, const FixationOptions& options,
                           const SearchStrategy& strategy) {
  const cv::Mat plane = ExtractChannel(frame_bgr, options.channel);
  const cv::Rect patch = SlicePatch(plane.size(), options.slice_count, slice, options.patch_size);
  if ((patch & cv::Rect(cv::Point(0, 0), plane.size())) != patch) {
    throw std::invalid_argument("PatchSelfConfidence: slice " + std::to_string(slice) +
                                "'s patch does not fit the frame");
  }
  const ReferencePatch reference(plane, SampleSet({patch}, options.sampling));
  const SearchResult found = strategy.Search(reference, plane, options.search);
  return found.found ? found.confidence : 0.0;
}

int ConfidentSlice(const cv::Mat& frame_bgr, const std::vector<int>& ranking,
                   const FixationOptions& options, const SearchStrategy& strategy) {
  if (ranking.empty()) throw std::invalid_argument("ConfidentSlice: the ranking is empty");
  for (const int slice : ranking) {
    if (PatchSelfConfidence(frame_bgr, slice, options, strategy) >=
        options.lock_regain_confidence) {
      return slice;
    }
  }
  return ranking.front();
}

std::optional<int> ConfidentSliceBesides(const cv::Mat& frame_bgr, const std::vector<int>& ranking,
                                         int lost, const FixationOptions& options,
                                         const SearchStrategy& strategy) {
  std::vector<int> others;
  for (const int slice : ranking) {
    if (slice != lost) others.push_back(slice);
  }
  if (others.empty()) return std::nullopt;
  return ConfidentSlice(frame_bgr, others, options, strategy);
}

}  // namespace kapfix
