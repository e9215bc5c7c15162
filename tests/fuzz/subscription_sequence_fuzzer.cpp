// libFuzzer target: the agent's stream socket handling a sequence of subscriptions from a few
// peers (FuzzSubscriptions). Built only by the fuzz preset; deploy/run-fuzz.sh runs it.

#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_entry_points.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)kapfix::fuzz::FuzzSubscriptions(data, size);
  return 0;
}
