// libFuzzer target: a station decoding what arrives on the agent's streams, every topic
// (FuzzStreamMessage). Built only by the fuzz preset; deploy/run-fuzz.sh runs it.

#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_entry_points.hpp"

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  kapfix::fuzz::SilenceProtobufLogs();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)kapfix::fuzz::FuzzStreamMessage(data, size);
  return 0;
}
