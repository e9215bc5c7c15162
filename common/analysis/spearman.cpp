#include "common/analysis/spearman.hpp"

#include <cmath>
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

}  // namespace kapfix
