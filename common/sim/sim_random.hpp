#pragma once

#include <cstdint>

namespace kapfix {

// Counter-based random numbers for the simulation: every value is a pure function of
// (seed, stream, index), so a frame's noise or jitter is the same whether frames are
// generated in order, out of order or on several threads. The mixing is SplitMix64's
// finaliser and the mappings below are our own, so the numbers are identical on every
// standard library (std:: distributions are not).

// 64 well-mixed bits for (seed, stream, index). `stream` separates independent uses
// (jitter, gusts, image noise …) of the same seed.
std::uint64_t SimHash(std::uint32_t seed, std::uint64_t stream, std::int64_t index);

// Uniform in [0, 1), 53 bits.
double SimUniform(std::uint32_t seed, std::uint64_t stream, std::int64_t index);

// Standard normal N(0, 1) by Box–Muller over two hashed uniforms.
double SimGaussian(std::uint32_t seed, std::uint64_t stream, std::int64_t index);

}  // namespace kapfix
