#pragma once

#include <chrono>
#include <cstdint>

namespace kapfix {

// Now on std::chrono::steady_clock [µs]: the one time base of frames, servo commands and
// watchdog deadlines (never the wall clock, which a board without a real-time clock sets late).
inline std::int64_t SteadyClockNowUs() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

}  // namespace kapfix
