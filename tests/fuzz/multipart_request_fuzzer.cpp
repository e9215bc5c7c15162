// libFuzzer target: the agent handling one multipart command request, from its frames to the
// reply (FuzzMultipartRequest). Built only by the fuzz preset; deploy/run-fuzz.sh runs it.

#include <cstddef>
#include <cstdint>

#include "tests/fuzz/fuzz_entry_points.hpp"

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  kapfix::fuzz::SilenceProtobufLogs();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)kapfix::fuzz::FuzzMultipartRequest(data, size);
  return 0;
}
