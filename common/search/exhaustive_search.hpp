#pragma once

#include "common/search/axis_search.hpp"

namespace kapfix {

// Strategy "all": every shift in [−R, +R) along each searched axis (thesis §4.4: 200 shifts
// of a 100×100 patch = 2,000,000 pixel comparisons at R = 100).
class ExhaustiveSearch final : public AxisSearch {
 public:
  std::string name() const override { return "all"; }

 protected:
  void SearchAxis(AxisProbe& probe, int range) const override;
};

}  // namespace kapfix
