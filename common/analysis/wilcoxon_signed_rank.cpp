#include "common/analysis/wilcoxon_signed_rank.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/analysis/ranks.hpp"

namespace kapfix {
namespace {

constexpr int kExactLimit = 20;  // 2²⁰ sign patterns as a count table: instant

// P(W+ ≤ w) under H0 for n untied ranks 1…n: counts of subsets of {1…n} by their sum.
double ExactLowerTail(int n, double w) {
  const int total = n * (n + 1) / 2;
  std::vector<double> counts(static_cast<std::size_t>(total) + 1, 0.0);
  counts[0] = 1.0;
  for (int r = 1; r <= n; ++r) {
    for (int s = total; s >= r; --s) counts[s] += counts[s - r];
  }
  double below = 0.0;
  for (int s = 0; s <= total && s <= static_cast<int>(std::floor(w + 1e-9)); ++s)
    below += counts[s];
  return below / std::pow(2.0, n);
}

}  // namespace

WilcoxonResult WilcoxonSignedRank(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) {
    throw std::invalid_argument("WilcoxonSignedRank: samples differ in length (" +
                                std::to_string(a.size()) + " vs " + std::to_string(b.size()) + ")");
  }
  if (a.empty()) throw std::invalid_argument("WilcoxonSignedRank: no pairs");
  std::vector<double> diffs;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double d = a[i] - b[i];
    if (std::isnan(d)) throw std::invalid_argument("WilcoxonSignedRank: a value is NaN");
    if (d != 0.0) diffs.push_back(d);
  }
  WilcoxonResult result;
  result.n = static_cast<int>(diffs.size());
  if (diffs.empty()) return result;
  std::vector<double> magnitudes;
  for (const double d : diffs) magnitudes.push_back(std::abs(d));
  const Ranking ranking = AverageRanks(magnitudes);
  for (std::size_t i = 0; i < diffs.size(); ++i) {
    (diffs[i] > 0 ? result.w_plus : result.w_minus) += ranking.ranks[i];
  }
  const double n = result.n;
  const double total = n * (n + 1.0) / 2.0;
  result.rank_biserial = (result.w_plus - result.w_minus) / total;
  const double w = std::min(result.w_plus, result.w_minus);
  if (result.n <= kExactLimit && ranking.tie_sum == 0.0) {
    result.exact = true;
    result.p_value = std::min(1.0, 2.0 * ExactLowerTail(result.n, w));
    return result;
  }
  const double mean = total / 2.0;
  const double variance = n * (n + 1.0) * (2.0 * n + 1.0) / 24.0 - ranking.tie_sum / 48.0;
  if (variance <= 0.0) return result;
  const double z = std::max(0.0, std::abs(result.w_plus - mean) - 0.5) / std::sqrt(variance);
  result.p_value = std::min(1.0, std::erfc(z / std::sqrt(2.0)));
  return result;
}

}  // namespace kapfix
