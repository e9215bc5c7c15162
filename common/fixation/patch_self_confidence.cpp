#include "common/fixation/patch_self_confidence.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "common/image/color_channel.hpp"
#include "common/matching/reference_patch.hpp"
#include "common/sampling/sample_set.hpp"
#include "common/selection/slice_geometry.hpp"

namespace kapfix {

namespace {

double PlaneSelfConfidence(const cv::Mat& plane, int slice, const FixationOptions& options,
                           const SearchStrategy& strategy) {
  const cv::Rect patch = SlicePatch(plane.size(), options.slice_count, slice, options.patch_size);
  if ((patch & cv::Rect(cv::Point(0, 0), plane.size())) != patch) {
    throw std::invalid_argument("PatchSelfConfidence: slice " + std::to_string(slice) +
                                "'s patch does not fit the frame");
  }
  const ReferencePatch reference(plane, SampleSet({patch}, options.sampling));
  const SearchResult found = strategy.Search(reference, plane, options.search);
  return found.found ? found.confidence : 0.0;
}

}  // namespace

double PatchSelfConfidence(const cv::Mat& frame_bgr, int slice, const FixationOptions& options,
                           const SearchStrategy& strategy) {
  return PlaneSelfConfidence(ExtractChannel(frame_bgr, options.channel), slice, options, strategy);
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

std::vector<double> PatchSelfConfidences(const cv::Mat& frame_bgr, const FixationOptions& options,
                                         const SearchStrategy& strategy) {
  const cv::Mat plane = ExtractChannel(frame_bgr, options.channel);
  std::vector<double> confidences;
  confidences.reserve(static_cast<std::size_t>(std::max(options.slice_count, 0)));
  for (int slice = 1; slice <= options.slice_count; ++slice) {
    confidences.push_back(PlaneSelfConfidence(plane, slice, options, strategy));
  }
  return confidences;
}

std::optional<int> NearestConfidentSlice(const std::vector<double>& confidences, int slice,
                                         double least) {
  const int count = static_cast<int>(confidences.size());
  if (slice < 1 || slice > count) {
    throw std::invalid_argument("NearestConfidentSlice: slice " + std::to_string(slice) +
                                " is not in 1 … " + std::to_string(count));
  }
  const auto confidence = [&](int s) { return confidences[static_cast<std::size_t>(s - 1)]; };
  for (int distance = 0; distance < count; ++distance) {
    std::optional<int> best;
    for (const int s : {slice - distance, slice + distance}) {
      if (s < 1 || s > count || confidence(s) < least) continue;
      if (!best || confidence(s) > confidence(*best)) best = s;
    }
    if (best) return best;
  }
  return std::nullopt;
}

std::optional<int> FirstConfidentSlice(const std::vector<double>& confidences,
                                       const std::vector<int>& ranking, double least) {
  for (const int slice : ranking) {
    if (slice < 1 || slice > static_cast<int>(confidences.size())) {
      throw std::invalid_argument("FirstConfidentSlice: slice " + std::to_string(slice) +
                                  " is not in 1 … " + std::to_string(confidences.size()));
    }
    if (confidences[static_cast<std::size_t>(slice - 1)] >= least) return slice;
  }
  return std::nullopt;
}

}  // namespace kapfix
