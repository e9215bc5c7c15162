#pragma once

#include <cstddef>
#include <functional>

namespace kapfix::bench {

// Runs fly(0) … fly(count − 1) on up to `jobs` threads (the calling thread alone when jobs is
// 1): each index exactly once, taken in index order, finishing in any order. fly(k) must
// write its result only where index k's result goes (the flights share nothing mutable).
// done(k) is called after fly(k) returned, one call at a time (under a lock) and in the order
// the flights finish, e.g. for progress. When a flight throws, no further flight starts, the
// running ones finish, and the exception of the lowest failed index is rethrown here.
void FlyInParallel(std::size_t count, int jobs, const std::function<void(std::size_t)>& fly,
                   const std::function<void(std::size_t)>& done);

}  // namespace kapfix::bench
