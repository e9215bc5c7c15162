#pragma once

#include <vector>

namespace kapfix {

// FFT score of a displacement graph [px] (SPEC §2.4): Σ |X_k| over the DFT bins k = 1 … T/2
// (T = graph.size(), integer division; the Nyquist bin of an even T is included). The DC bin
// is left out because a constant drift is not a tracking error. Unnormalised: a sine of
// amplitude a [px] over whole periods scores a·T/2 [px]. The thesis divides by 1000 for its
// tables; we do not, so compare with its figures after dividing. 0 for fewer than 2 samples.
double FftScore(const std::vector<double>& graph);

}  // namespace kapfix
