#include "common/analysis/statistics.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace kapfix {
namespace {

void RequireValues(const std::vector<double>& values, const char* function) {
  if (values.empty()) throw std::invalid_argument(std::string(function) + ": no values");
}

// std::sort needs a strict weak order, which NaN breaks.
void RequireNoNaN(const std::vector<double>& values, const char* function) {
  if (std::any_of(values.begin(), values.end(), [](double v) { return std::isnan(v); })) {
    throw std::invalid_argument(std::string(function) + ": values contain NaN");
  }
}

}  // namespace

double Mean(const std::vector<double>& values) {
  RequireValues(values, "Mean");
  double sum = 0.0;
  for (const double v : values) sum += v;
  return sum / static_cast<double>(values.size());
}

double StandardDeviation(const std::vector<double>& values) {
  RequireValues(values, "StandardDeviation");
  if (values.size() < 2) {
    throw std::invalid_argument(
        "StandardDeviation: the sample standard deviation needs at "
        "least 2 values, got 1");
  }
  // Two passes: subtracting the mean first avoids the cancellation of Σx² − n·mean².
  const double mean = Mean(values);
  double squares = 0.0;
  for (const double v : values) squares += (v - mean) * (v - mean);
  return std::sqrt(squares / static_cast<double>(values.size() - 1));
}

double Median(std::vector<double> values) {
  RequireValues(values, "Median");
  RequireNoNaN(values, "Median");
  return Percentile(std::move(values), 50.0);
}

double Percentile(std::vector<double> values, double p) {
  RequireValues(values, "Percentile");
  RequireNoNaN(values, "Percentile");
  if (!(p >= 0.0 && p <= 100.0)) {
    throw std::invalid_argument("Percentile: p must be in [0, 100], got " + std::to_string(p));
  }
  std::sort(values.begin(), values.end());
  const double rank = p / 100.0 * static_cast<double>(values.size() - 1);
  const auto below = static_cast<std::size_t>(std::floor(rank));
  const std::size_t above = std::min(below + 1, values.size() - 1);
  const double fraction = rank - static_cast<double>(below);
  // An exact rank returns its value untouched (0 · ∞ would make NaN next to an infinity).
  if (fraction == 0.0) return values[below];
  return values[below] + fraction * (values[above] - values[below]);
}

double RootMeanSquare(const std::vector<double>& values) {
  RequireValues(values, "RootMeanSquare");
  double squares = 0.0;
  for (const double v : values) squares += v * v;
  return std::sqrt(squares / static_cast<double>(values.size()));
}

}  // namespace kapfix
