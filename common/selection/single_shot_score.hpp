#pragma once

#include <opencv2/core.hpp>

#include "common/matching/error_curve.hpp"
#include "common/sampling/sampling_pattern.hpp"
#include "common/search/search_strategy.hpp"

namespace kapfix {

// How well a patch would track, judged from ONE frame (SPEC §2.6, the thesis's future work):
// the patch is compared with its own frame along the search axis, so the error curve's global
// minimum is at shift 0 (distance 0) and the question is how that minimum stands out.
//
//  - rival: the lowest local minimum at |shift| > 2 (a plateau counts as one minimum; an end of
//    the curve counts when it is lower than its neighbour); without one, the highest distance
//    at |shift| > 2 (a single clean basin).
//  - distinctness = clamp(rival / median of the curve, 0, 1): a repetitive texture has a rival
//    near 0, a featureless patch a median of 0 (distinctness 0).
//  - basin_width_px w: mean over both sides of how far [px] the curve rises strictly from 0
//    before it first stops rising. A plateau ends the basin as a fall does: it gives a descent
//    no slope to follow. A wide basin is what lets a coarse search (h23, pyr) land in it.
//  - score = distinctness · (1 − e^(−w / 8 px)), in [0, 1); higher is better.
struct SingleShotScore {
  double score = 0.0;
  double distinctness = 0.0;    // [0, 1]
  double basin_width_px = 0.0;  // [px]
  // A rival valley rises less than 0.2 of the curve's highest distance above the self-match
  // (MatchConfidence's criterion, at the fixation loop's trust threshold): a repetitive
  // texture whose neighbouring period matches nearly as well. Marked, not scored away.
  bool ambiguous = false;
};

// The score of a self-comparison curve (shift 0 must be on it, else all zero; all zero too when
// no shift with |shift| > 2 was scored, as nothing can be said about rivals).
SingleShotScore SingleShotScoreFromCurve(const ErrorCurve& curve);

// The score of `patch` in `plane` (CV_8UC1, CV_16UC1 or CV_8UC3), sampled by `sampling`, along
// search.axis within ±search.range (search.origin is ignored: the self-match is at 0). kBoth
// scores both axes and keeps the weaker one, since a 2-D search has to lock on both.
// Throws std::invalid_argument for a patch outside the plane or invalid options.
SingleShotScore ComputeSingleShotScore(const cv::Mat& plane, cv::Rect patch,
                                       const SamplingOptions& sampling,
                                       const SearchOptions& search);

}  // namespace kapfix
