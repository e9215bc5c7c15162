#pragma once

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace kapfix {

// How clearly the global minimum of sampled distances stands out (SPEC §2.3), in [0, 1]:
// 1 − best / rival, where `rival` is the lowest local minimum of the sampled curve lying more
// than `exclusion` positions from the best one (a repetitive texture's second valley), or the
// highest sampled distance when there is no such minimum (a single clean basin). 0 means the
// rival is as good as the best: the lock is ambiguous.
double MatchConfidence(const std::map<int, std::int64_t>& curve, int exclusion = 2);
// The same over (position, distance) pairs in increasing position: no tree to build for a
// curve computed in order.
double MatchConfidence(const std::vector<std::pair<int, std::int64_t>>& curve, int exclusion = 2);

}  // namespace kapfix
