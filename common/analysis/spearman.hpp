#pragma once

#include <vector>

namespace kapfix {

// Spearman's rank correlation in [−1, 1]: the Pearson correlation of the average ranks (exact
// with ties, unlike the 1 − 6Σd² / (n(n² − 1)) shortcut). Used to ask whether one score
// orders slices as another does (e.g. DC count vs FFT score, SPEC §2.6).
// Throws std::invalid_argument for different lengths, fewer than 2 pairs, NaN, or a constant
// sequence (no ranking to correlate).
double SpearmanCorrelation(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace kapfix

namespace kapfix {

// Spearman's ρ with its two-sided p-value against "no monotone association".
struct SpearmanResult {
  double rho = 0.0;
  // Exact for n ≤ 9: the share of all n! orderings of b's ranks (ties kept) whose |ρ| reaches
  // the observed |ρ|. Beyond, Student's t with n − 2 dof on t = ρ·sqrt((n − 2) / (1 − ρ²)).
  double p_value = 1.0;
  bool exact = false;
};

// Same preconditions as SpearmanCorrelation (throws std::invalid_argument).
SpearmanResult SpearmanTest(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace kapfix
