#include "common/search/exhaustive_search.hpp"

namespace kapfix {

void ExhaustiveSearch::SearchAxis(AxisProbe& probe, int range) const {
  const int c = probe.centre_position();
  std::int64_t distance = 0;
  for (int s = c - range; s < c + range; ++s) probe.Evaluate(s, &distance);
}

}  // namespace kapfix
