#include "common/matching/ssd_kernel.hpp"

#include <algorithm>

#include "common/image/target_clones.hpp"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define KAPFIX_HAVE_AVX2_DOT 1
#else
#define KAPFIX_HAVE_AVX2_DOT 0
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

KAPFIX_KERNEL std::int64_t DotRowsPortable(const std::int16_t* ref, int padded, int rows,
                                           const std::uint8_t* cur, std::size_t cur_step) {
  std::int64_t total = 0;
  for (int r = 0; r < rows; ++r) {
    std::int32_t sum = 0;
    for (int i = 0; i < padded; ++i) {
      sum += static_cast<std::int32_t>(ref[i]) * static_cast<std::int16_t>(cur[i]);
    }
    total += sum;
    ref += padded;
    cur += cur_step;
  }
  return total;
}

KAPFIX_KERNEL std::int64_t SsdRowsMaskedPortable(const std::int16_t* ref, const std::int16_t* mask,
                                                 int padded, int rows, const std::uint8_t* cur,
                                                 std::size_t cur_step) {
  std::int64_t total = 0;
  for (int r = 0; r < rows; ++r) {
    std::int32_t sum = 0;
    for (int i = 0; i < padded; ++i) {
      const std::int32_t d = ref[i] - static_cast<std::int32_t>(cur[i]);
      sum += d * (d & mask[i]);
    }
    total += sum;
    ref += padded;
    cur += cur_step;
  }
  return total;
}

namespace {

#if KAPFIX_HAVE_AVX2_DOT
// Written with intrinsics: autovectorised, the reduction is closed (a horizontal add and a
// remainder loop) at the end of every row, which cost more than the products on 100-pixel
// rows. Here one register accumulates the whole block and is reduced once. kMasked: Σ d² over
// the mask's lanes (SsdRowsMasked), else Σ ref · cur (DotRows). kBlocks > 0 fixes the row
// length at compile time (16 · kBlocks), so that short rows (pyr's reduced levels: 2 and 4
// vectors) run unrolled, without a loop per row.
template <bool kMasked, int kBlocks>
__attribute__((target("avx2"))) std::int64_t RowsAvx2(const std::int16_t* ref,
                                                      const std::int16_t* mask, int padded,
                                                      int rows, const std::uint8_t* cur,
                                                      std::size_t cur_step) {
  // 32-bit lanes: flush to 64 bits before rows · padded · 255² could reach 2³¹ (a 100×100
  // patch never needs to; the division is skipped then: it costs as much as a short row).
  constexpr int kMaxPixels = 0x7fffffff / (255 * 255);
  const int rows_per_flush = rows * padded <= kMaxPixels ? rows : std::max(1, kMaxPixels / padded);
  const int length = kBlocks > 0 ? 16 * kBlocks : padded;
  std::int64_t total = 0;
  for (int r0 = 0; r0 < rows; r0 += rows_per_flush) {
    __m256i acc = _mm256_setzero_si256();
    const int r1 = std::min(rows, r0 + rows_per_flush);
    for (int r = r0; r < r1; ++r) {
      for (int i = 0; i < length; i += 16) {
        const __m256i c = _mm256_cvtepu8_epi16(
            _mm_loadu_si128(reinterpret_cast<const __m128i*>(cur + i)));                  // NOLINT
        const __m256i a = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(ref + i));  // NOLINT
        if constexpr (kMasked) {
          const __m256i m =
              _mm256_loadu_si256(reinterpret_cast<const __m256i*>(mask + i));  // NOLINT
          const __m256i d = _mm256_sub_epi16(a, c);
          acc = _mm256_add_epi32(acc, _mm256_madd_epi16(d, _mm256_and_si256(d, m)));
        } else {
          acc = _mm256_add_epi32(acc, _mm256_madd_epi16(a, c));
        }
      }
      ref += padded;
      cur += cur_step;
    }
    const __m128i half =
        _mm_add_epi32(_mm256_castsi256_si128(acc), _mm256_extracti128_si256(acc, 1));
    const __m128i quarter = _mm_add_epi32(half, _mm_unpackhi_epi64(half, half));
    total += _mm_cvtsi128_si32(quarter) + _mm_cvtsi128_si32(_mm_srli_si128(quarter, 4));
  }
  return total;
}

template <bool kMasked>
std::int64_t RowsAvx2(const std::int16_t* ref, const std::int16_t* mask, int padded, int rows,
                      const std::uint8_t* cur, std::size_t cur_step) {
  switch (padded) {
    case 32:
      return RowsAvx2<kMasked, 2>(ref, mask, padded, rows, cur, cur_step);
    case 64:
      return RowsAvx2<kMasked, 4>(ref, mask, padded, rows, cur, cur_step);
    default:
      return RowsAvx2<kMasked, 0>(ref, mask, padded, rows, cur, cur_step);
  }
}

bool HasAvx2() {
  static const bool avx2 = __builtin_cpu_supports("avx2") != 0;
  return avx2;
}
#endif

}  // namespace

std::int64_t SsdRowsMasked(const std::int16_t* ref, const std::int16_t* mask, int padded, int rows,
                           const std::uint8_t* cur, std::size_t cur_step) {
#if KAPFIX_HAVE_AVX2_DOT
  if (HasAvx2()) return RowsAvx2<true>(ref, mask, padded, rows, cur, cur_step);
#endif
  return SsdRowsMaskedPortable(ref, mask, padded, rows, cur, cur_step);
}

std::int64_t DotRows(const std::int16_t* ref, int padded, int rows, const std::uint8_t* cur,
                     std::size_t cur_step) {
#if KAPFIX_HAVE_AVX2_DOT
  if (HasAvx2()) return RowsAvx2<false>(ref, nullptr, padded, rows, cur, cur_step);
#endif
  return DotRowsPortable(ref, padded, rows, cur, cur_step);
}

KAPFIX_KERNEL void AddSquares(const std::uint8_t* row, int n, std::int32_t* acc) {
  for (int i = 0; i < n; ++i) {
    const std::int32_t v = row[i];
    acc[i] += v * v;
  }
}

KAPFIX_KERNEL std::int64_t SumSquares(const std::uint8_t* row, int n) {
  std::int32_t sum = 0;  // n · 255² < 2³¹ for any row shorter than 33 000 pixels
  for (int i = 0; i < n; ++i) {
    const std::int32_t v = row[i];
    sum += v * v;
  }
  return sum;
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
