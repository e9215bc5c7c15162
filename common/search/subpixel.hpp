#pragma once

#include <cstdint>

namespace kapfix {

// Offset in (−0.5, 0.5) of the vertex of the parabola through (−1, left), (0, centre),
// (+1, right), for a centre that is a minimum of the three; 0 when the three are collinear or
// the centre is not the lowest.
double ParabolaVertexOffset(std::int64_t left, std::int64_t centre, std::int64_t right);

}  // namespace kapfix
