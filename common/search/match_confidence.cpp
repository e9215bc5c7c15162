#include "common/search/match_confidence.hpp"

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <limits>

namespace kapfix {

namespace {

template <typename Curve>
double Confidence(const Curve& curve, int exclusion) {
  if (curve.size() < 2) return 0.0;
  const auto best = std::min_element(
      curve.begin(), curve.end(), [](const auto& a, const auto& b) { return a.second < b.second; });
  std::int64_t rival = std::numeric_limits<std::int64_t>::max();
  std::int64_t highest = 0;
  for (auto it = curve.begin(); it != curve.end(); ++it) {
    highest = std::max(highest, it->second);
    if (std::abs(it->first - best->first) <= exclusion) continue;
    const bool below_left = it == curve.begin() || it->second <= std::prev(it)->second;
    const bool below_right = std::next(it) == curve.end() || it->second <= std::next(it)->second;
    if (below_left && below_right) rival = std::min(rival, it->second);
  }
  if (rival == std::numeric_limits<std::int64_t>::max()) rival = highest;
  if (rival <= 0) return 0.0;
  const double ratio =
      std::clamp(1.0 - static_cast<double>(best->second) / static_cast<double>(rival), 0.0, 1.0);
  // Sensor noise, blur and brightness add about the same to every distance, which pulls the
  // ratio towards 0 everywhere but barely hides a repetitive texture's rival. The rival's
  // rise above the best as a share of the curve's whole rise does not see that floor: a
  // rival one texture period away that is nearly as good scores near 0 whatever the
  // absolute distances.
  const double rise = static_cast<double>(highest - best->second);
  const double contrast =
      rise > 0 ? std::clamp(static_cast<double>(rival - best->second) / rise, 0.0, 1.0) : 0.0;
  return std::min(ratio, contrast);
}

}  // namespace

double MatchConfidence(const std::map<int, std::int64_t>& curve, int exclusion) {
  return Confidence(curve, exclusion);
}

double MatchConfidence(const std::vector<std::pair<int, std::int64_t>>& curve, int exclusion) {
  return Confidence(curve, exclusion);
}

}  // namespace kapfix
