#pragma once

#include <vector>

namespace kapfix {

// Number of direction changes (DC, SPEC §1) of a displacement graph [px].
//
// hysteresis_px = 0: every local extremum counts — a sign change of the first difference,
// zero differences skipped (a plateau between a rise and a fall is one extremum).
//
// hysteresis_px = h > 0: a turning-point counter with hysteresis (SPEC §2.4). It follows the
// running extreme in the current direction and counts a change only once the graph has come
// back from that extreme by at least h px; until the first move of h px the direction is
// unknown and nothing counts. Whole-pixel rounding makes a smooth swing's graph wobble by
// ±1 px, which the plain count reads as extra extrema; h = 1.5 ignores those wobbles.
//
// Throws std::invalid_argument for a negative or non-finite h.
int CountDirectionChanges(const std::vector<double>& graph, double hysteresis_px = 0.0);

}  // namespace kapfix
