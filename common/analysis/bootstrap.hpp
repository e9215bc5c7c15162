#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace kapfix {

// Percentile bootstrap (Efron): resample the values with replacement, take the statistic of
// each resample, read the interval off the sorted resampled statistics. Used for the effect
// sizes of `kapfix-analyze compare` (resampling runs, i.e. seeds, never frames: frames of one
// run are autocorrelated and would give intervals far too narrow).
struct BootstrapOptions {
  int resamples = 4000;
  double confidence = 0.95;  // in (0, 1)
  // The resampling draws index = generator() mod n from std::mt19937_64 (whose output the
  // standard fixes), so an interval is the same on every platform for the same seed.
  std::uint64_t seed = 1;

  bool IsValid(std::string* error) const;
};

struct ConfidenceInterval {
  double estimate = 0.0;  // the statistic on the values themselves
  double low = 0.0;
  double high = 0.0;
};

// Interval for the mean. For a paired difference pass the per-pair differences. Throws
// std::invalid_argument for empty input, NaN or invalid options.
ConfidenceInterval BootstrapMean(const std::vector<double>& values,
                                 const BootstrapOptions& options);

}  // namespace kapfix
