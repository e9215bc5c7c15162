#include "common/sim/sim_random.hpp"

#include <cmath>
#include <numbers>

namespace kapfix {
namespace {

std::uint64_t SplitMix64(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double ToUnit(std::uint64_t bits) {
  return static_cast<double>(bits >> 11) * 0x1.0p-53;  // top 53 bits → [0, 1)
}

}  // namespace

std::uint64_t SimHash(std::uint32_t seed, std::uint64_t stream, std::int64_t index) {
  // Chained rather than XOR-ed together, so that (seed, stream, index) triples that differ
  // in several places cannot cancel out.
  std::uint64_t h = SplitMix64(seed);
  h = SplitMix64(h ^ stream);
  return SplitMix64(h ^ static_cast<std::uint64_t>(index));
}

double SimUniform(std::uint32_t seed, std::uint64_t stream, std::int64_t index) {
  return ToUnit(SimHash(seed, stream, index));
}

double SimGaussian(std::uint32_t seed, std::uint64_t stream, std::int64_t index) {
  const std::uint64_t h = SimHash(seed, stream, index);
  // Two uniforms from one index: the second from a re-mix of the first's bits.
  const double u1 = 1.0 - ToUnit(h);  // (0, 1]: keeps log finite
  const double u2 = ToUnit(SplitMix64(h));
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace kapfix
