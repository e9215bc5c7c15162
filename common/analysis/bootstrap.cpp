#include "common/analysis/bootstrap.hpp"

#include <cmath>
#include <random>
#include <stdexcept>

#include "common/analysis/statistics.hpp"

namespace kapfix {

bool BootstrapOptions::IsValid(std::string* error) const {
  if (resamples < 100 || resamples > 1000000) {
    if (error) *error = "bootstrap resamples must be 100…1000000, got " + std::to_string(resamples);
    return false;
  }
  if (!(confidence > 0.0 && confidence < 1.0)) {
    if (error) *error = "bootstrap confidence must be in (0, 1), got " + std::to_string(confidence);
    return false;
  }
  return true;
}

ConfidenceInterval BootstrapMean(const std::vector<double>& values,
                                 const BootstrapOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("BootstrapMean: " + error);
  if (values.empty()) throw std::invalid_argument("BootstrapMean: no values");
  for (const double v : values) {
    if (std::isnan(v)) throw std::invalid_argument("BootstrapMean: a value is NaN");
  }
  std::mt19937_64 generator(options.seed);
  const std::uint64_t n = values.size();
  std::vector<double> means;
  means.reserve(static_cast<std::size_t>(options.resamples));
  for (int r = 0; r < options.resamples; ++r) {
    double sum = 0.0;
    for (std::uint64_t i = 0; i < n; ++i) sum += values[generator() % n];
    means.push_back(sum / static_cast<double>(n));
  }
  const double tail = 50.0 * (1.0 - options.confidence);  // [%] on each side
  ConfidenceInterval interval;
  interval.estimate = Mean(values);
  interval.low = Percentile(means, tail);
  interval.high = Percentile(std::move(means), 100.0 - tail);
  return interval;
}

}  // namespace kapfix
