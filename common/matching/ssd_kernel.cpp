#include "common/matching/ssd_kernel.hpp"

namespace kapfix {

std::int64_t SsdRun(const std::uint8_t* a, const std::uint8_t* b, int n) {
  // 32-bit lanes: 255² · n stays below 2³¹ for any n < 33 000 (a frame row is shorter).
  std::int32_t sum = 0;
  for (int i = 0; i < n; ++i) {
    const std::int32_t d = static_cast<std::int32_t>(a[i]) - static_cast<std::int32_t>(b[i]);
    sum += d * d;
  }
  return sum;
}

std::int64_t SsdRun(const std::uint16_t* a, const std::uint16_t* b, int n) {
  std::int64_t sum = 0;
  for (int i = 0; i < n; ++i) {
    const std::int64_t d = static_cast<std::int64_t>(a[i]) - static_cast<std::int64_t>(b[i]);
    sum += d * d;
  }
  return sum;
}

std::int64_t SsdGather(const std::uint8_t* values, const std::uint8_t* base,
                       const std::int32_t* offsets, int n) {
  std::int64_t sum = 0;
  for (int i = 0; i < n; ++i) {
    const std::int32_t d =
        static_cast<std::int32_t>(values[i]) - static_cast<std::int32_t>(base[offsets[i]]);
    sum += d * d;
  }
  return sum;
}

std::int64_t SsdGather(const std::uint16_t* values, const std::uint16_t* base,
                       const std::int32_t* offsets, int n) {
  std::int64_t sum = 0;
  for (int i = 0; i < n; ++i) {
    const std::int64_t d =
        static_cast<std::int64_t>(values[i]) - static_cast<std::int64_t>(base[offsets[i]]);
    sum += d * d;
  }
  return sum;
}

__attribute__((optimize("no-tree-vectorize"))) std::int64_t SsdRunScalar(const std::uint8_t* a,
                                                                          const std::uint8_t* b,
                                                                          int n) {
  std::int32_t sum = 0;
  for (int i = 0; i < n; ++i) {
    const std::int32_t d = static_cast<std::int32_t>(a[i]) - static_cast<std::int32_t>(b[i]);
    sum += d * d;
  }
  return sum;
}

}  // namespace kapfix
