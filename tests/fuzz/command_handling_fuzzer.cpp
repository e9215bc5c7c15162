// libFuzzer target: the agent handling a command request's bytes, from decoding to the call
// into AgentControl (FuzzCommand). Built only by the fuzz preset; deploy/run-fuzz.sh runs it.

#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_entry_points.hpp"

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  kapfix::fuzz::SilenceProtobufLogs();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)kapfix::fuzz::FuzzCommand(data, size);
  return 0;
}
