#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "common/sampling/sampling_pattern.hpp"
#include "common/search/search_strategy.hpp"

namespace kapfix {

// How a search strategy fares on a swing whose truth is known (SPEC §3): the reference patch
// is taken from frame 0 and every later frame is searched against it (fixation on a stored
// reference, servos off). Used by `kapfix-analyze swing`, `ssp --validate`, `compare` and the
// matcher benchmark, so that all of them report the same figures the same way.
struct SwingEvaluationOptions {
  SearchOptions search;
  SamplingOptions sampling;
  double gross_fail_px = 10.0;  // [px] |error| above this is a lost minimum
  double within_px = 2.0;       // [px] |error| up to this counts as on target
  bool time_searches = true;    // measure each search with a steady clock

  bool IsValid(std::string* error) const;
};

struct SwingEvaluation {
  std::vector<double> errors_px;  // [px] measured − true displacement along the axis, t ≥ 1
  std::vector<double> search_us;  // [µs] time of each search (empty if not timed)
  double mean_abs_err_px = 0.0;
  double within_2px_pct = 0.0;  // [%] of frames with |error| ≤ within_px
  double gross_fail_pct = 0.0;  // [%] of frames with |error| > gross_fail_px
  double pixels_per_estimate = 0.0;
  double median_us_per_estimate = 0.0;
  int not_found = 0;  // searches that could score no shift (counted as gross)
};

// `planes` are the swing's frames after ExtractChannel; `truth[t]` is where frame 0's content
// appears in frame t minus where it was ([px]); `patch` is the reference patch in frame 0.
// The error is read along x for SearchAxis kX and kBoth, along y for kY.
SwingEvaluation EvaluateSwing(const std::vector<cv::Mat>& planes,
                              const std::vector<cv::Point2d>& truth, cv::Rect patch,
                              const SearchStrategy& strategy, const SwingEvaluationOptions& options,
                              const std::function<void(int, int)>& progress = nullptr);

}  // namespace kapfix
