#include "common/evaluation/swing_evaluation.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "common/matching/reference_patch.hpp"

namespace kapfix {

bool SwingEvaluationOptions::IsValid(std::string* error) const {
  if (!search.IsValid(error) || !sampling.IsValid(error)) return false;
  if (!(gross_fail_px > 0.0) || !(within_px > 0.0)) {
    if (error) *error = "swing evaluation thresholds must be positive";
    return false;
  }
  return true;
}

SwingEvaluation EvaluateSwing(const std::vector<cv::Mat>& planes,
                              const std::vector<cv::Point2d>& truth, cv::Rect patch,
                              const SearchStrategy& strategy, const SwingEvaluationOptions& options,
                              const std::function<void(int, int)>& progress) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  if (planes.size() < 2 || truth.size() != planes.size()) {
    throw std::invalid_argument("swing evaluation needs ≥ 2 frames and one truth per frame");
  }
  const ReferencePatch reference(planes[0], SampleSet({patch}, options.sampling));
  const bool along_y = options.search.axis == SearchAxis::kY;
  SwingEvaluation result;
  const int frames = static_cast<int>(planes.size());
  std::int64_t pixels = 0;
  int within = 0;
  int gross = 0;
  double abs_sum = 0.0;
  for (int t = 1; t < frames; ++t) {
    const auto start = std::chrono::steady_clock::now();
    const SearchResult found = strategy.Search(reference, planes[t], options.search);
    const auto stop = std::chrono::steady_clock::now();
    if (options.time_searches) {
      result.search_us.push_back(std::chrono::duration<double, std::micro>(stop - start).count());
    }
    pixels += found.pixels_compared;
    double err = 0.0;
    if (found.found) {
      err = along_y ? found.displacement.y - truth[t].y : found.displacement.x - truth[t].x;
    } else {
      ++result.not_found;
      err = std::numeric_limits<double>::infinity();
    }
    result.errors_px.push_back(err);
    if (std::abs(err) <= options.within_px) ++within;
    if (!(std::abs(err) <= options.gross_fail_px)) ++gross;
    if (std::isfinite(err)) abs_sum += std::abs(err);
    if (progress) progress(t, frames - 1);
  }
  const double n = frames - 1;
  const int finite = frames - 1 - result.not_found;
  result.mean_abs_err_px = finite > 0 ? abs_sum / finite : 0.0;
  result.within_2px_pct = 100.0 * within / n;
  result.gross_fail_pct = 100.0 * gross / n;
  result.pixels_per_estimate = static_cast<double>(pixels) / n;
  if (!result.search_us.empty()) {
    std::vector<double> sorted = result.search_us;
    std::nth_element(sorted.begin(),
                     sorted.begin() + static_cast<std::ptrdiff_t>(sorted.size() / 2), sorted.end());
    result.median_us_per_estimate = sorted[sorted.size() / 2];
  }
  return result;
}

}  // namespace kapfix
