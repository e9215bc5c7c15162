#pragma once

#include <cstddef>
#include <cstdint>

namespace kapfix {

// The distance's inner loops (SPEC §2.1). Integer arithmetic only. ssd_kernel.cpp is compiled
// with -O3 whatever the build type, because GCC 12 does not vectorise these loops at -O2
// (SPEC §8); bench/matcher_benchmark reports the speed-up over a scalar build of the same loop.

// Σ (a[i] − b[i])² over n contiguous pixels.
std::int64_t SsdRun(const std::uint8_t* a, const std::uint8_t* b, int n);
std::int64_t SsdRun(const std::uint16_t* a, const std::uint16_t* b, int n);

// Σ over `rows` runs of (values − base[offsets[r] …])²: run r compares lengths[r] pixels of
// `values` (consumed in order) with those starting at base + offsets[r]. One call per search
// position instead of one per row.
std::int64_t SsdRows(const std::uint8_t* values, const std::uint8_t* base,
                     const std::int32_t* offsets, const std::int32_t* lengths, int rows);
std::int64_t SsdRows(const std::uint16_t* values, const std::uint16_t* base,
                     const std::int32_t* offsets, const std::int32_t* lengths, int rows);

// Σ (a − b)² over a width × height block of two strided planes (steps in elements).
std::int64_t SsdBlock(const std::uint8_t* a, std::size_t a_step, const std::uint8_t* b,
                      std::size_t b_step, int width, int height);
std::int64_t SsdBlock(const std::uint16_t* a, std::size_t a_step, const std::uint16_t* b,
                      std::size_t b_step, int width, int height);

// Sliding SSD of one reference row against one current row for `shifts` consecutive
// horizontal shifts: out[s] += Σ_k (ref[k] − cur[s + k])², k < width. `cur` must hold
// width + shifts − 1 pixels. The loop runs over the shifts, so it vectorises however short the
// row is (a coarse pyramid level's rows are 25 pixels). 16-bit planes only: 8-bit ones use
// SlidingSsd, several times faster.
void SsdSlide(const std::uint16_t* ref, int width, const std::uint16_t* cur, int shifts,
              std::int64_t* out);

// Σ_r Σ_{i<padded} ref[r·padded + i] · cur[r·cur_step + i] over `rows` rows: the cross term of
// SSD = Σr² − 2Σr·c + Σc² (see SlidingSsd). `ref` holds 8-bit values widened to 16 bits and
// zero-padded to `padded` per row, so that a row of any width runs as whole vectors and the
// pixels read past the width count zero; `cur` must be readable for `padded` pixels per row.
// 32-bit row sums: keep padded · 255² below 2³¹.
std::int64_t DotRows(const std::int16_t* ref, int padded, int rows, const std::uint8_t* cur,
                     std::size_t cur_step);

// Σ_r Σ_{i<padded} (ref[r·padded + i] − cur[r·cur_step + i])² over the lanes where mask[i] is
// all ones (−1), the rows' first `width` pixels; the zero lanes beyond count nothing. One
// position of SlidingSsd without its running sums. Same layout and limits as DotRows.
std::int64_t SsdRowsMasked(const std::int16_t* ref, const std::int16_t* mask, int padded, int rows,
                           const std::uint8_t* cur, std::size_t cur_step);

// DotRows and SsdRowsMasked without their AVX2 intrinsics: what CPUs without AVX2 (and other
// architectures) run. Exposed so that the tests compare both paths on any machine.
std::int64_t DotRowsPortable(const std::int16_t* ref, int padded, int rows, const std::uint8_t* cur,
                             std::size_t cur_step);
std::int64_t SsdRowsMaskedPortable(const std::int16_t* ref, const std::int16_t* mask, int padded,
                                   int rows, const std::uint8_t* cur, std::size_t cur_step);

// acc[i] += row[i]² for i < n (Σc² column by column, for SlidingSsd).
void AddSquares(const std::uint8_t* row, int n, std::int32_t* acc);
// Σ row[i]² for i < n.
std::int64_t SumSquares(const std::uint8_t* row, int n);

// Σ (values[i] − base[offsets[i]])² over n scattered pixels.
std::int64_t SsdGather(const std::uint8_t* values, const std::uint8_t* base,
                       const std::int32_t* offsets, int n);
std::int64_t SsdGather(const std::uint16_t* values, const std::uint16_t* base,
                       const std::int32_t* offsets, int n);

// The same contiguous loop with vectorisation switched off: the benchmark's yardstick for
// checking that the shipped build vectorises SsdRun.
std::int64_t SsdRunScalar(const std::uint8_t* a, const std::uint8_t* b, int n);

}  // namespace kapfix
