#include "common/analysis/ranks.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace kapfix {

Ranking AverageRanks(const std::vector<double>& values) {
  if (std::any_of(values.begin(), values.end(), [](double v) { return std::isnan(v); })) {
    throw std::invalid_argument("AverageRanks: values contain NaN");
  }
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  Ranking ranking;
  ranking.ranks.resize(values.size());
  std::size_t first = 0;
  while (first < order.size()) {
    std::size_t last = first + 1;  // one past the run of values equal to values[order[first]]
    while (last < order.size() && values[order[last]] == values[order[first]]) ++last;
    // Positions first … last − 1 are 0-based; their 1-based ranks average to this.
    const double average = 0.5 * static_cast<double>(first + last + 1);
    for (std::size_t i = first; i < last; ++i) ranking.ranks[order[i]] = average;
    const auto t = static_cast<double>(last - first);
    ranking.tie_sum += t * t * t - t;
    first = last;
  }
  return ranking;
}

}  // namespace kapfix
