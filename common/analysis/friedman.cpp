#include "common/analysis/friedman.hpp"

#include <boost/math/distributions/chi_squared.hpp>
#include <stdexcept>
#include <string>

#include "common/analysis/ranks.hpp"

namespace kapfix {

FriedmanResult Friedman(const std::vector<std::vector<double>>& treatments) {
  if (treatments.size() < 2) {
    throw std::invalid_argument("Friedman: needs at least 2 treatments, got " +
                                std::to_string(treatments.size()));
  }
  const std::size_t blocks = treatments.front().size();
  if (blocks < 2) {
    throw std::invalid_argument("Friedman: needs at least 2 blocks, got " + std::to_string(blocks));
  }
  for (std::size_t j = 0; j < treatments.size(); ++j) {
    if (treatments[j].size() != blocks) {
      throw std::invalid_argument("Friedman: treatment " + std::to_string(j) + " has " +
                                  std::to_string(treatments[j].size()) + " blocks, the first " +
                                  std::to_string(blocks));
    }
  }
  const std::size_t k = treatments.size();
  std::vector<double> rank_sums(k, 0.0);
  double tie_sum = 0.0;
  for (std::size_t i = 0; i < blocks; ++i) {
    std::vector<double> block;
    for (std::size_t j = 0; j < k; ++j) block.push_back(treatments[j][i]);
    const Ranking ranking = AverageRanks(block);  // throws on NaN
    for (std::size_t j = 0; j < k; ++j) rank_sums[j] += ranking.ranks[j];
    tie_sum += ranking.tie_sum;
  }
  const auto n = static_cast<double>(blocks);
  const auto kd = static_cast<double>(k);
  FriedmanResult result;
  result.degrees_of_freedom = static_cast<int>(k) - 1;
  for (const double r : rank_sums) result.mean_ranks.push_back(r / n);
  const double correction = 1.0 - tie_sum / (n * (kd * kd * kd - kd));
  if (correction <= 0.0) return result;  // every block entirely tied
  double squares = 0.0;
  for (const double r : rank_sums) squares += r * r;
  double chi = 12.0 / (n * kd * (kd + 1.0)) * squares - 3.0 * n * (kd + 1.0);
  if (chi < 0.0) chi = 0.0;  // rounding when the rank sums are all equal
  result.chi_square = chi / correction;
  result.kendall_w = result.chi_square / (n * (kd - 1.0));
  const boost::math::chi_squared chi2(result.degrees_of_freedom);
  result.p_value = boost::math::cdf(boost::math::complement(chi2, result.chi_square));
  return result;
}

}  // namespace kapfix
