#pragma once

#include <cstdint>
#include <map>
#include <utility>
#include <vector>

namespace kapfix {

// How clearly the global minimum of sampled distances stands out (SPEC §2.3), in [0, 1]:
// the smaller of 1 − best / rival and (rival − best) / (highest − best), where `rival` is the
// lowest local minimum of the sampled curve lying more than `exclusion` positions from the
// best one (a repetitive texture's second valley), or the highest sampled distance when
// there is no such minimum (a single clean basin: the second term is then 1). 0 means the
// rival is as good as the best: the lock is ambiguous. The second term sees ambiguity
// whatever the absolute distances (issue 9): a noise floor common to every position lifts
// best and rival alike and hides a rival from the ratio, not from the share of the rise.
double MatchConfidence(const std::map<int, std::int64_t>& curve, int exclusion = 2);
// The same over (position, distance) pairs in increasing position: no tree to build for a
// curve computed in order.
double MatchConfidence(const std::vector<std::pair<int, std::int64_t>>& curve, int exclusion = 2);

}  // namespace kapfix
