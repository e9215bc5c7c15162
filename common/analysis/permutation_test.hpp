#pragma once

#include <cstdint>
#include <vector>

namespace kapfix {

// Pooled test of "does a slice score order slices as their fixation error does?" over several
// images at once (SSP validation): the statistic is the mean over images of Spearman's ρ
// between score and outcome; under H0 the outcomes are exchangeable among one image's slices,
// so the null distribution permutes outcomes within each image, never across images.
struct PooledPermutationResult {
  double mean_rho = 0.0;  // the observed statistic
  // Two-sided, (1 + #{|T*| ≥ |T|}) / (1 + permutations): never 0, valid for a finite count.
  double p_value = 1.0;
  int groups_used = 0;  // images with a defined ρ (neither sequence constant)
  int permutations = 0;
};

// scores[g][i], outcomes[g][i]: slice i of image g. Groups with a constant sequence carry no
// ranking and are left out. Throws std::invalid_argument for mismatched sizes, NaN, fewer than
// 100 permutations or no usable group.
PooledPermutationResult PooledSpearmanPermutationTest(
    const std::vector<std::vector<double>>& scores,
    const std::vector<std::vector<double>>& outcomes, int permutations, std::uint64_t seed);

}  // namespace kapfix
