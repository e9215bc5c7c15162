#pragma once

#include <vector>

namespace kapfix {

// Wilcoxon's signed-rank test for paired samples (two strategies flown on the same seeds):
// is the median of the differences a − b zero? Zero differences are dropped (Wilcoxon's
// convention), the others ranked by |d| with average ranks for ties.
struct WilcoxonResult {
  double w_plus = 0.0;   // sum of the ranks of the positive differences
  double w_minus = 0.0;  // sum of the ranks of the negative differences
  int n = 0;             // non-zero differences
  // Two-sided. Exact (every one of the 2ⁿ sign patterns counted) when n ≤ 20 and no |d| is
  // tied; otherwise the normal approximation with tie correction and continuity correction.
  double p_value = 1.0;
  bool exact = false;
  // Effect size, the matched-pairs rank-biserial correlation (W+ − W−) / (W+ + W−) in [−1, 1]:
  // +1 when every a is above its b.
  double rank_biserial = 0.0;
};

// Throws std::invalid_argument for different lengths, empty input or NaN. With no non-zero
// difference: p = 1, n = 0.
WilcoxonResult WilcoxonSignedRank(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace kapfix
