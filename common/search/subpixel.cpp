#include "common/search/subpixel.hpp"

#include <algorithm>

namespace kapfix {

double ParabolaVertexOffset(std::int64_t left, std::int64_t centre, std::int64_t right) {
  if (centre > left || centre > right) return 0.0;
  const double curvature =
      static_cast<double>(left) - 2.0 * static_cast<double>(centre) + static_cast<double>(right);
  if (curvature <= 0.0) return 0.0;
  const double offset = 0.5 * static_cast<double>(left - right) / curvature;
  return std::clamp(offset, -0.5, 0.5);
}

}  // namespace kapfix
