#include "common/selection/direction_changes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace kapfix {
namespace {

int CountPlain(const std::vector<double>& graph) {
  int changes = 0;
  int last_sign = 0;  // sign of the last non-zero difference
  for (std::size_t i = 1; i < graph.size(); ++i) {
    const double d = graph[i] - graph[i - 1];
    const int sign = (d > 0) - (d < 0);
    if (sign == 0) continue;
    if (last_sign != 0 && sign != last_sign) ++changes;
    last_sign = sign;
  }
  return changes;
}

int CountWithHysteresis(const std::vector<double>& graph, double h) {
  int changes = 0;
  int direction = 0;  // +1 rising, −1 falling, 0 not yet known
  double extreme = 0.0;
  double low = 0.0;  // while the direction is unknown: lowest and highest value so far
  double high = 0.0;
  for (std::size_t i = 0; i < graph.size(); ++i) {
    const double v = graph[i];
    if (i == 0) {
      low = high = v;
      continue;
    }
    if (direction == 0) {
      if (v - low >= h) {
        direction = +1;
        extreme = v;
      } else if (high - v >= h) {
        direction = -1;
        extreme = v;
      }
      low = std::min(low, v);
      high = std::max(high, v);
    } else if (direction * (v - extreme) > 0) {
      extreme = v;  // still moving the same way: the turning point has not come yet
    } else if (std::abs(v - extreme) >= h) {
      ++changes;
      direction = -direction;
      extreme = v;
    }
  }
  return changes;
}

}  // namespace

int CountDirectionChanges(const std::vector<double>& graph, double hysteresis_px) {
  if (!std::isfinite(hysteresis_px) || hysteresis_px < 0.0) {
    throw std::invalid_argument("CountDirectionChanges: hysteresis must be ≥ 0 px, got " +
                                std::to_string(hysteresis_px));
  }
  return hysteresis_px == 0.0 ? CountPlain(graph) : CountWithHysteresis(graph, hysteresis_px);
}

}  // namespace kapfix
