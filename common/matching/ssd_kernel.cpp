#include "common/matching/ssd_kernel.hpp"

// Each kernel is built twice, for baseline x86-64 (SSE2) and for AVX2, and the loader picks
// the best one the CPU supports: the shipped binary runs on any x86-64 board and uses the
// wider registers where they exist.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__) && \
    !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)
#define KAPFIX_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define KAPFIX_KERNEL
#endif

namespace kapfix {

KAPFIX_KERNEL std::int64_t SsdRun(const std::uint8_t* a, const std::uint8_t* b, int n) {
  // 32-bit lanes: 255² · n stays below 2³¹ for any n < 33 000 (a frame row is shorter).
  std::int32_t sum = 0;
  for (int i = 0; i < n; ++i) {
    const std::int32_t d = static_cast<std::int32_t>(a[i]) - static_cast<std::int32_t>(b[i]);
    sum += d * d;
  }
  return sum;
}

KAPFIX_KERNEL std::int64_t SsdRun(const std::uint16_t* a, const std::uint16_t* b, int n) {
  std::int64_t sum = 0;
  for (int i = 0; i < n; ++i) {
    const std::int64_t d = static_cast<std::int64_t>(a[i]) - static_cast<std::int64_t>(b[i]);
    sum += d * d;
  }
  return sum;
}

namespace {

template <typename T, typename Acc>
inline Acc SsdInner(const T* a, const T* b, int n) {
  Acc sum = 0;
  for (int i = 0; i < n; ++i) {
    const Acc d = static_cast<Acc>(a[i]) - static_cast<Acc>(b[i]);
    sum += d * d;
  }
  return sum;
}

}  // namespace

KAPFIX_KERNEL std::int64_t SsdRows(const std::uint8_t* values, const std::uint8_t* base,
                                   const std::int32_t* offsets, const std::int32_t* lengths,
                                   int rows) {
  std::int64_t sum = 0;
  for (int r = 0; r < rows; ++r) {
    sum += SsdInner<std::uint8_t, std::int32_t>(values, base + offsets[r], lengths[r]);
    values += lengths[r];
  }
  return sum;
}

KAPFIX_KERNEL std::int64_t SsdRows(const std::uint16_t* values, const std::uint16_t* base,
                                   const std::int32_t* offsets, const std::int32_t* lengths,
                                   int rows) {
  std::int64_t sum = 0;
  for (int r = 0; r < rows; ++r) {
    sum += SsdInner<std::uint16_t, std::int64_t>(values, base + offsets[r], lengths[r]);
    values += lengths[r];
  }
  return sum;
}

KAPFIX_KERNEL std::int64_t SsdBlock(const std::uint8_t* a, std::size_t a_step,
                                    const std::uint8_t* b, std::size_t b_step, int width,
                                    int height) {
  std::int64_t sum = 0;
  for (int y = 0; y < height; ++y) {
    sum += SsdInner<std::uint8_t, std::int32_t>(a + y * a_step, b + y * b_step, width);
  }
  return sum;
}

KAPFIX_KERNEL std::int64_t SsdBlock(const std::uint16_t* a, std::size_t a_step,
                                    const std::uint16_t* b, std::size_t b_step, int width,
                                    int height) {
  std::int64_t sum = 0;
  for (int y = 0; y < height; ++y) {
    sum += SsdInner<std::uint16_t, std::int64_t>(a + y * a_step, b + y * b_step, width);
  }
  return sum;
}

KAPFIX_KERNEL void SsdSlide(const std::uint8_t* ref, int width, const std::uint8_t* cur, int shifts,
                            std::int32_t* out) {
  for (int k = 0; k < width; ++k) {
    const std::int32_t r = ref[k];
    const std::uint8_t* c = cur + k;
    for (int s = 0; s < shifts; ++s) {
      const std::int32_t d = r - static_cast<std::int32_t>(c[s]);
      out[s] += d * d;
    }
  }
}

KAPFIX_KERNEL void SsdSlide(const std::uint16_t* ref, int width, const std::uint16_t* cur,
                            int shifts, std::int64_t* out) {
  for (int k = 0; k < width; ++k) {
    const std::int64_t r = ref[k];
    const std::uint16_t* c = cur + k;
    for (int s = 0; s < shifts; ++s) {
      const std::int64_t d = r - static_cast<std::int64_t>(c[s]);
      out[s] += d * d;
    }
  }
}

KAPFIX_KERNEL std::int64_t SsdGather(const std::uint8_t* values, const std::uint8_t* base,
                                     const std::int32_t* offsets, int n) {
  // Four independent sums keep the loads of scattered pixels overlapping. 32-bit partial sums
  // are safe for n / 4 · 255² < 2³¹, i.e. n < 132 000 sampled pixels.
  std::int32_t s0 = 0;
  std::int32_t s1 = 0;
  std::int32_t s2 = 0;
  std::int32_t s3 = 0;
  int i = 0;
  for (; i + 4 <= n; i += 4) {
    const std::int32_t d0 = values[i] - base[offsets[i]];
    const std::int32_t d1 = values[i + 1] - base[offsets[i + 1]];
    const std::int32_t d2 = values[i + 2] - base[offsets[i + 2]];
    const std::int32_t d3 = values[i + 3] - base[offsets[i + 3]];
    s0 += d0 * d0;
    s1 += d1 * d1;
    s2 += d2 * d2;
    s3 += d3 * d3;
  }
  std::int64_t sum = static_cast<std::int64_t>(s0) + s1 + s2 + s3;
  for (; i < n; ++i) {
    const std::int64_t d = values[i] - base[offsets[i]];
    sum += d * d;
  }
  return sum;
}

KAPFIX_KERNEL std::int64_t SsdGather(const std::uint16_t* values, const std::uint16_t* base,
                                     const std::int32_t* offsets, int n) {
  std::int64_t sum = 0;
  for (int i = 0; i < n; ++i) {
    const std::int64_t d =
        static_cast<std::int64_t>(values[i]) - static_cast<std::int64_t>(base[offsets[i]]);
    sum += d * d;
  }
  return sum;
}

#if defined(__clang__)
#define KAPFIX_NO_VECTORIZE
#else
#define KAPFIX_NO_VECTORIZE __attribute__((optimize("no-tree-vectorize")))
#endif

KAPFIX_NO_VECTORIZE std::int64_t SsdRunScalar(const std::uint8_t* a, const std::uint8_t* b, int n) {
  std::int32_t sum = 0;
#if defined(__clang__)
#pragma clang loop vectorize(disable) interleave(disable)
#endif
  for (int i = 0; i < n; ++i) {
    const std::int32_t d = static_cast<std::int32_t>(a[i]) - static_cast<std::int32_t>(b[i]);
    sum += d * d;
  }
  return sum;
}

}  // namespace kapfix
