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
