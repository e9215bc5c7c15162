#pragma once

#include <vector>

namespace kapfix {

// Ranks shared by the rank-based tests (Kruskal–Wallis, Spearman).
struct Ranking {
  std::vector<double> ranks;  // 1-based, in input order; tied values share their average rank
  double tie_sum = 0.0;       // Σ(t³ − t) over the groups of t tied values (0 without ties)
};

// Throws std::invalid_argument on NaN (it has no rank).
Ranking AverageRanks(const std::vector<double>& values);

}  // namespace kapfix
