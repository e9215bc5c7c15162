#pragma once

#include <vector>

namespace kapfix {

// Kruskal–Wallis one-way analysis of variance on ranks (SPEC §2.10): do k independent groups
// come from the same distribution? The thesis used it (through MINITAB) to compare search
// strategies and best vs worst SSP slices (p = 0.009, §5).
struct KruskalWallisResult {
  double h = 0.0;  // H = 12 / (N(N+1)) · Σ R_i² / n_i − 3(N+1), average ranks for ties
  double h_corrected = 0.0;  // H / (1 − Σ(t³ − t) / (N³ − N)): MINITAB's "adjusted for ties"
  double p_value = 1.0;      // upper tail of χ²(k − 1) at h_corrected
  int degrees_of_freedom = 0;  // k − 1
};

// Needs at least two groups, none empty, no NaN; throws std::invalid_argument otherwise.
// When every value is the same the test has nothing to rank: h = h_corrected = 0 and
// p_value = 1 (no evidence of a difference) instead of the formula's 0 / 0.
// The χ² approximation is the usual one; it is rough for groups of fewer than ~5 values.
KruskalWallisResult KruskalWallis(const std::vector<std::vector<double>>& groups);

}  // namespace kapfix
