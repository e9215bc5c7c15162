#include "common/analysis/spearman.hpp"

#include <algorithm>
#include <boost/math/distributions/students_t.hpp>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

#include "common/analysis/ranks.hpp"

namespace kapfix {

double SpearmanCorrelation(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) {
    throw std::invalid_argument("SpearmanCorrelation: sequences differ in length (" +
                                std::to_string(a.size()) + " vs " + std::to_string(b.size()) + ")");
  }
  if (a.size() < 2) {
    throw std::invalid_argument("SpearmanCorrelation: needs at least 2 pairs, got " +
                                std::to_string(a.size()));
  }
  const std::vector<double> ra = AverageRanks(a).ranks;
  const std::vector<double> rb = AverageRanks(b).ranks;
  // Both rank sequences average (n + 1) / 2, whatever the ties.
  const double mean = 0.5 * static_cast<double>(a.size() + 1);
  double cov = 0.0;
  double var_a = 0.0;
  double var_b = 0.0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    cov += (ra[i] - mean) * (rb[i] - mean);
    var_a += (ra[i] - mean) * (ra[i] - mean);
    var_b += (rb[i] - mean) * (rb[i] - mean);
  }
  if (var_a == 0.0 || var_b == 0.0) {
    throw std::invalid_argument("SpearmanCorrelation: a sequence is constant");
  }
  return cov / std::sqrt(var_a * var_b);
}

namespace {

constexpr std::size_t kExactLimit = 9;  // 9! = 362,880 orderings

// Pearson correlation of two rank sequences with mean (n + 1) / 2 and the given variances.
double RankCorrelation(const std::vector<double>& ra, const std::vector<double>& rb, double var_a,
                       double var_b) {
  const double mean = 0.5 * static_cast<double>(ra.size() + 1);
  double cov = 0.0;
  for (std::size_t i = 0; i < ra.size(); ++i) cov += (ra[i] - mean) * (rb[i] - mean);
  return cov / std::sqrt(var_a * var_b);
}

double RankVariance(const std::vector<double>& ranks) {
  const double mean = 0.5 * static_cast<double>(ranks.size() + 1);
  double var = 0.0;
  for (const double r : ranks) var += (r - mean) * (r - mean);
  return var;
}

}  // namespace

SpearmanResult SpearmanTest(const std::vector<double>& a, const std::vector<double>& b) {
  SpearmanResult result;
  result.rho = SpearmanCorrelation(a, b);  // checks the preconditions
  const std::size_t n = a.size();
  const std::vector<double> ra = AverageRanks(a).ranks;
  std::vector<double> rb = AverageRanks(b).ranks;
  const double var_a = RankVariance(ra);
  const double var_b = RankVariance(rb);
  if (n <= kExactLimit) {
    result.exact = true;
    std::sort(rb.begin(), rb.end());
    // Every distinct ordering of b's ranks is equally likely under H0; counting distinct
    // orderings of the multiset is the same share as counting all n! with their repeats.
    long long hits = 0;
    long long total = 0;
    const double observed = std::abs(result.rho) - 1e-12;
    do {
      ++total;
      if (std::abs(RankCorrelation(ra, rb, var_a, var_b)) >= observed) ++hits;
    } while (std::next_permutation(rb.begin(), rb.end()));
    result.p_value = static_cast<double>(hits) / static_cast<double>(total);
    return result;
  }
  const double dof = static_cast<double>(n) - 2.0;
  const double r2 = result.rho * result.rho;
  if (r2 >= 1.0) {
    result.p_value = 0.0;
    return result;
  }
  const double t = std::abs(result.rho) * std::sqrt(dof / (1.0 - r2));
  const boost::math::students_t student(dof);
  result.p_value = 2.0 * boost::math::cdf(boost::math::complement(student, t));
  return result;
}

}  // namespace kapfix
