#include "common/analysis/permutation_test.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include "common/analysis/spearman.hpp"

namespace kapfix {
namespace {

bool IsConstant(const std::vector<double>& values) {
  for (const double v : values) {
    if (v != values.front()) return false;
  }
  return true;
}

// Fisher–Yates with index = generator() mod (i + 1): the same shuffle on every platform
// (std::shuffle's use of the generator is not fixed by the standard).
void Shuffle(std::vector<double>* values, std::mt19937_64* generator) {
  for (std::size_t i = values->size(); i > 1; --i) {
    std::swap((*values)[i - 1], (*values)[(*generator)() % i]);
  }
}

}  // namespace

PooledPermutationResult PooledSpearmanPermutationTest(
    const std::vector<std::vector<double>>& scores,
    const std::vector<std::vector<double>>& outcomes, int permutations, std::uint64_t seed) {
  if (scores.size() != outcomes.size()) {
    throw std::invalid_argument("PooledSpearmanPermutationTest: " + std::to_string(scores.size()) +
                                " score groups vs " + std::to_string(outcomes.size()) +
                                " outcome groups");
  }
  if (permutations < 100) {
    throw std::invalid_argument("PooledSpearmanPermutationTest: needs at least 100 permutations");
  }
  std::vector<std::size_t> used;
  for (std::size_t g = 0; g < scores.size(); ++g) {
    if (scores[g].size() != outcomes[g].size()) {
      throw std::invalid_argument("PooledSpearmanPermutationTest: group " + std::to_string(g) +
                                  " has " + std::to_string(scores[g].size()) + " scores and " +
                                  std::to_string(outcomes[g].size()) + " outcomes");
    }
    for (std::size_t i = 0; i < scores[g].size(); ++i) {
      if (std::isnan(scores[g][i]) || std::isnan(outcomes[g][i])) {
        throw std::invalid_argument("PooledSpearmanPermutationTest: a value is NaN");
      }
    }
    if (scores[g].size() >= 2 && !IsConstant(scores[g]) && !IsConstant(outcomes[g])) {
      used.push_back(g);
    }
  }
  if (used.empty()) {
    throw std::invalid_argument("PooledSpearmanPermutationTest: no group with a defined ranking");
  }
  auto statistic = [&](const std::vector<std::vector<double>>& outs) {
    double sum = 0.0;
    for (const std::size_t g : used) sum += SpearmanCorrelation(scores[g], outs[g]);
    return sum / static_cast<double>(used.size());
  };
  PooledPermutationResult result;
  result.groups_used = static_cast<int>(used.size());
  result.permutations = permutations;
  result.mean_rho = statistic(outcomes);
  std::mt19937_64 generator(seed);
  std::vector<std::vector<double>> shuffled = outcomes;
  int extreme = 0;
  const double observed = std::abs(result.mean_rho) - 1e-12;
  for (int p = 0; p < permutations; ++p) {
    for (const std::size_t g : used) Shuffle(&shuffled[g], &generator);
    if (std::abs(statistic(shuffled)) >= observed) ++extreme;
  }
  result.p_value = (1.0 + extreme) / (1.0 + permutations);
  return result;
}

}  // namespace kapfix
