#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <vector>

#include "common/fixation/fixation_loop.hpp"
#include "common/search/search_strategy.hpp"

namespace kapfix {

// [0, 1] How confidently the fixation's search finds slice `slice`'s patch in the very frame it
// is cut from (BGR or grey, 8 bit): the best the loop can hope for in flight, where noise, blur
// and roll only lower it. SSP judges a slice over the free swing, but the patch the loop stores
// is whatever part of the scene is under the slice in the reference frame (issue 9: home.jpg
// after SSP, 0.19 and 0.31 where its lock was never confirmed, 0.47 where it held).
// Throws std::invalid_argument when the slice's patch does not fit the frame.
double PatchSelfConfidence(const cv::Mat& frame_bgr, int slice, const FixationOptions& options,
                           const SearchStrategy& strategy);

// The first slice of `ranking` (best first, e.g. SSP's) whose patch in `frame_bgr` is found at
// options.lock_regain_confidence or more, the confidence that confirms a lock; ranking's first
// when none is. Throws std::invalid_argument for an empty ranking.
int ConfidentSlice(const cv::Mat& frame_bgr, const std::vector<int>& ranking,
                   const FixationOptions& options, const SearchStrategy& strategy);
// The same over `ranking` without `lost`, the slice a lock was just lost on (SSP after a lost
// lock: whatever SSP thinks of its graph, a flat patch reads no motion and so no direction
// change, it is not the answer); none when no other slice is ranked.
std::optional<int> ConfidentSliceBesides(const cv::Mat& frame_bgr, const std::vector<int>& ranking,
                                         int lost, const FixationOptions& options,
                                         const SearchStrategy& strategy);

// [0, 1] PatchSelfConfidence of every slice in `frame_bgr`: element i is slice i + 1's.
std::vector<double> PatchSelfConfidences(const cv::Mat& frame_bgr, const FixationOptions& options,
                                         const SearchStrategy& strategy);

// The slice to hold a view by when the patch of `slice` [1 … confidences.size()] may be weak:
// `slice` itself when its confidence (as PatchSelfConfidences) is `least` or more, else the
// nearest slice whose is, the more confident of two equally near; none when no slice passes.
// Nearest, because the servos turn and do not roll: under the camera's roll a patch far from
// the frame's centre is held while the centre, the view, drifts by the roll times the distance.
std::optional<int> NearestConfidentSlice(const std::vector<double>& confidences, int slice,
                                         double least);
// The first slice of `ranking` (best first, e.g. SSP's) whose confidence (as
// PatchSelfConfidences) is `least` or more; none when no ranked slice passes. Throws
// std::invalid_argument for a ranked slice outside 1 … confidences.size().
std::optional<int> FirstConfidentSlice(const std::vector<double>& confidences,
                                       const std::vector<int>& ranking, double least);

}  // namespace kapfix
