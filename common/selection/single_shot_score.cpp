#include "common/selection/single_shot_score.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <stdexcept>
#include <string>

#include "common/matching/reference_patch.hpp"

namespace kapfix {
namespace {

// Within this many pixels of the self-match a minimum belongs to the global one's basin.
constexpr int kRivalExclusionPx = 2;
// [px] basin half-width at which the width factor reaches 1 − 1/e.
constexpr double kBasinScalePx = 8.0;
// A rival valley below this share of the highest distance is ambiguous (as
// FixationOptions::lock_lost_confidence's default for MatchConfidence).
constexpr double kAmbiguousContrast = 0.2;

double Median(std::vector<std::int64_t> values) {
  const std::size_t mid = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid), values.end());
  const auto upper = static_cast<double>(values[mid]);
  if (values.size() % 2 == 1) return upper;
  const auto lower = static_cast<double>(
      *std::max_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(mid)));
  return 0.5 * (lower + upper);
}

// Lowest local minimum that reaches beyond the exclusion zone, or the highest distance there.
double Rival(const ErrorCurve& curve) {
  const auto& d = curve.distances;
  const int n = static_cast<int>(d.size());
  std::int64_t rival = std::numeric_limits<std::int64_t>::max();
  std::int64_t highest = 0;
  for (int i = 0; i < n; ++i) {
    if (std::abs(curve.shifts[i]) > kRivalExclusionPx) highest = std::max(highest, d[i]);
  }
  // Walk runs of equal distances so that a flat valley floor is one minimum.
  for (int first = 0; first < n;) {
    int last = first;
    while (last + 1 < n && d[last + 1] == d[first]) ++last;
    const bool below_left = first == 0 || d[first - 1] > d[first];
    const bool below_right = last == n - 1 || d[last + 1] > d[first];
    const bool is_minimum = below_left && below_right;  // the curve's ends count alike
    bool beyond = false;
    for (int i = first; i <= last; ++i) beyond |= std::abs(curve.shifts[i]) > kRivalExclusionPx;
    if (is_minimum && beyond) rival = std::min(rival, d[first]);
    first = last + 1;
  }
  return static_cast<double>(rival == std::numeric_limits<std::int64_t>::max() ? highest : rival);
}

// [px] how far the curve keeps rising strictly from index `zero` in direction `step` (±1).
double RiseLength(const ErrorCurve& curve, int zero, int step) {
  const int n = static_cast<int>(curve.distances.size());
  int k = zero;
  while (k + step >= 0 && k + step < n && curve.distances[k + step] > curve.distances[k]) {
    k += step;
  }
  return std::abs(curve.shifts[k] - curve.shifts[zero]);
}

}  // namespace

SingleShotScore SingleShotScoreFromCurve(const ErrorCurve& curve) {
  SingleShotScore result;
  const auto zero_it = std::find(curve.shifts.begin(), curve.shifts.end(), 0);
  if (zero_it == curve.shifts.end()) return result;
  const bool has_rivals = std::any_of(curve.shifts.begin(), curve.shifts.end(),
                                      [](int s) { return std::abs(s) > kRivalExclusionPx; });
  if (!has_rivals) return result;
  const int zero = static_cast<int>(zero_it - curve.shifts.begin());
  const double median = Median(curve.distances);
  result.distinctness = median > 0.0 ? std::clamp(Rival(curve) / median, 0.0, 1.0) : 0.0;
  result.basin_width_px = 0.5 * (RiseLength(curve, zero, -1) + RiseLength(curve, zero, +1));
  result.score = result.distinctness * (1.0 - std::exp(-result.basin_width_px / kBasinScalePx));
  std::int64_t highest = 0;
  for (std::size_t i = 0; i < curve.shifts.size(); ++i) {
    if (std::abs(curve.shifts[i]) > kRivalExclusionPx)
      highest = std::max(highest, curve.distances[i]);
  }
  // The self-match is at distance 0, so the rival's rise is the rival itself.
  result.ambiguous =
      highest > 0 && Rival(curve) < kAmbiguousContrast * static_cast<double>(highest);
  return result;
}

SingleShotScore ComputeSingleShotScore(const cv::Mat& plane, cv::Rect patch,
                                       const SamplingOptions& sampling,
                                       const SearchOptions& search) {
  std::string error;
  if (!sampling.IsValid(&error) || !search.IsValid(&error)) {
    throw std::invalid_argument("ComputeSingleShotScore: " + error);
  }
  const cv::Rect frame(cv::Point(0, 0), plane.size());
  if (patch.empty() || (patch & frame) != patch) {
    throw std::invalid_argument("ComputeSingleShotScore: patch lies outside the frame");
  }
  const ReferencePatch reference(plane, SampleSet({patch}, sampling));
  SingleShotScore weakest;
  bool first = true;
  for (const bool along_x : {true, false}) {
    if (along_x && search.axis == SearchAxis::kY) continue;
    if (!along_x && search.axis == SearchAxis::kX) continue;
    const SingleShotScore s =
        SingleShotScoreFromCurve(ComputeErrorCurve(reference, plane, along_x, search.range));
    if (first || s.score < weakest.score) weakest = s;
    first = false;
  }
  return weakest;
}

}  // namespace kapfix
