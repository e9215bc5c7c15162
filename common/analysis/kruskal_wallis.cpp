#include "common/analysis/kruskal_wallis.hpp"

#include <boost/math/distributions/chi_squared.hpp>
#include <stdexcept>
#include <string>

#include "common/analysis/ranks.hpp"

namespace kapfix {

KruskalWallisResult KruskalWallis(const std::vector<std::vector<double>>& groups) {
  if (groups.size() < 2) {
    throw std::invalid_argument("KruskalWallis: needs at least 2 groups, got " +
                                std::to_string(groups.size()));
  }
  std::vector<double> pooled;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (groups[g].empty()) {
      throw std::invalid_argument("KruskalWallis: group " + std::to_string(g) + " is empty");
    }
    pooled.insert(pooled.end(), groups[g].begin(), groups[g].end());
  }
  const Ranking ranking = AverageRanks(pooled);  // throws on NaN

  KruskalWallisResult result;
  result.degrees_of_freedom = static_cast<int>(groups.size()) - 1;
  const auto n_total = static_cast<double>(pooled.size());
  const double correction = 1.0 - ranking.tie_sum / (n_total * n_total * n_total - n_total);
  // Every value tied (N ≥ 2 here, so only then is the correction 0): H would be 0 / 0.
  if (correction <= 0.0) return result;

  double sum = 0.0;  // Σ R_i² / n_i
  std::size_t offset = 0;
  for (const std::vector<double>& group : groups) {
    double rank_sum = 0.0;
    for (std::size_t i = 0; i < group.size(); ++i) rank_sum += ranking.ranks[offset + i];
    sum += rank_sum * rank_sum / static_cast<double>(group.size());
    offset += group.size();
  }
  result.h = 12.0 / (n_total * (n_total + 1.0)) * sum - 3.0 * (n_total + 1.0);
  // Rounding can leave a tiny negative H when the rank sums are exactly proportional.
  if (result.h < 0.0) result.h = 0.0;
  result.h_corrected = result.h / correction;
  const boost::math::chi_squared chi2(result.degrees_of_freedom);
  result.p_value = boost::math::cdf(boost::math::complement(chi2, result.h_corrected));
  return result;
}

}  // namespace kapfix
