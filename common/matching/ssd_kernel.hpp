#pragma once

#include <cstdint>

namespace kapfix {

// The distance's inner loops (SPEC §2.1). Integer arithmetic only. ssd_kernel.cpp is compiled
// with -O3 whatever the build type, because GCC 12 does not vectorise these loops at -O2
// (SPEC §8); bench/matcher_benchmark reports the speed-up over a scalar build of the same loop.

// Σ (a[i] − b[i])² over n contiguous pixels.
std::int64_t SsdRun(const std::uint8_t* a, const std::uint8_t* b, int n);
std::int64_t SsdRun(const std::uint16_t* a, const std::uint16_t* b, int n);

// Σ (values[i] − base[offsets[i]])² over n scattered pixels.
std::int64_t SsdGather(const std::uint8_t* values, const std::uint8_t* base,
                       const std::int32_t* offsets, int n);
std::int64_t SsdGather(const std::uint16_t* values, const std::uint16_t* base,
                       const std::int32_t* offsets, int n);

// The same contiguous loop with vectorisation switched off: the benchmark's yardstick for
// checking that the shipped build vectorises SsdRun.
std::int64_t SsdRunScalar(const std::uint8_t* a, const std::uint8_t* b, int n);

}  // namespace kapfix
