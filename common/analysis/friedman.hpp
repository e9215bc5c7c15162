#pragma once

#include <vector>

namespace kapfix {

// Friedman's test for k treatments measured on the same n blocks (a paired design: e.g. every
// search strategy flown on the same n seeds). Ranks within each block, average ranks for ties.
struct FriedmanResult {
  // χ²_F = 12 / (n k (k + 1)) · Σ R_j² − 3 n (k + 1), divided by the tie correction
  // 1 − Σ(t³ − t) / (n (k³ − k)) (Σ over the tied groups of every block).
  double chi_square = 0.0;
  double p_value = 1.0;            // upper tail of χ²(k − 1)
  int degrees_of_freedom = 0;      // k − 1
  double kendall_w = 0.0;          // effect size, χ²_F / (n (k − 1)) in [0, 1]
  std::vector<double> mean_ranks;  // per treatment, R_j / n (1 = lowest values)
};

// treatments[j][i]: treatment j on block i. Needs ≥ 2 treatments, ≥ 2 blocks, every treatment
// with the same number of blocks, no NaN; throws std::invalid_argument otherwise. When every
// block is one big tie there is nothing to rank: χ² = 0, p = 1.
FriedmanResult Friedman(const std::vector<std::vector<double>>& treatments);

}  // namespace kapfix
