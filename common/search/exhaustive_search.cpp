#include "common/search/exhaustive_search.hpp"

namespace kapfix {

void ExhaustiveSearch::SearchAxis(AxisProbe& probe, int range) const {
  const int c = probe.centre_position();
  probe.EvaluateRun(c - range, c + range - 1);
}

}  // namespace kapfix
