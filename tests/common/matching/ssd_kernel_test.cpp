#include "common/matching/ssd_kernel.hpp"

#include <gtest/gtest.h>

#include <opencv2/core.hpp>
#include <tuple>
#include <vector>

namespace kapfix {
namespace {

struct Rows {
  int padded = 0;
  int width = 0;
  int rows = 0;
  std::vector<std::int16_t> ref;   // rows × padded, zero beyond width
  std::vector<std::int16_t> mask;  // −1 below width
  std::vector<std::uint8_t> cur;   // rows × step
  std::size_t step = 0;
};

std::size_t RefIndex(const Rows& r, int y, int x) {
  return static_cast<std::size_t>(y) * static_cast<std::size_t>(r.padded) +
         static_cast<std::size_t>(x);
}

// Rows of `value` (or noise when value < 0) against a current plane of the opposite extreme:
// products and squares at their largest, where a 32-bit overflow would show.
Rows MakeRows(int width, int rows, int value, int seed) {
  Rows r;
  r.width = width;
  r.rows = rows;
  r.padded = (width + 15) / 16 * 16;
  r.step = static_cast<std::size_t>(r.padded) + 7;
  r.ref.assign(static_cast<std::size_t>(r.padded) * static_cast<std::size_t>(rows), 0);
  r.mask.assign(static_cast<std::size_t>(r.padded), 0);
  r.cur.resize(r.step * static_cast<std::size_t>(rows));
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  for (int x = 0; x < width; ++x) r.mask[static_cast<std::size_t>(x)] = -1;
  for (int y = 0; y < rows; ++y) {
    for (int x = 0; x < width; ++x) {
      r.ref[RefIndex(r, y, x)] =
          static_cast<std::int16_t>(value >= 0 ? value : rng.uniform(0, 256));
    }
  }
  for (std::uint8_t& c : r.cur) {
    c = static_cast<std::uint8_t>(value >= 0 ? 255 - value : rng.uniform(0, 256));
  }
  return r;
}

std::int64_t NaiveDot(const Rows& r) {
  std::int64_t sum = 0;
  for (int y = 0; y < r.rows; ++y) {
    for (int x = 0; x < r.width; ++x) {
      sum += static_cast<std::int64_t>(r.ref[RefIndex(r, y, x)]) *
             r.cur[static_cast<std::size_t>(y) * r.step + static_cast<std::size_t>(x)];
    }
  }
  return sum;
}

std::int64_t NaiveSsd(const Rows& r) {
  std::int64_t sum = 0;
  for (int y = 0; y < r.rows; ++y) {
    for (int x = 0; x < r.width; ++x) {
      const std::int64_t d =
          static_cast<std::int64_t>(r.ref[RefIndex(r, y, x)]) -
          r.cur[static_cast<std::size_t>(y) * r.step + static_cast<std::size_t>(x)];
      sum += d * d;
    }
  }
  return sum;
}

TEST(SsdKernelTest, PaddedRowKernelsEqualTheDefinitionOnBothPaths) {
  // 150 × 300 at the extremes passes 2³¹ in 32-bit lanes: the kernels must flush in time.
  for (const auto& [width, rows, value] :
       {std::tuple{25, 25, -1}, std::tuple{100, 100, -1}, std::tuple{16, 3, 0},
        std::tuple{150, 300, 255}, std::tuple{150, 300, 0}, std::tuple{1, 1, 200}}) {
    const Rows r = MakeRows(width, rows, value, width + rows);
    const std::int64_t dot = NaiveDot(r);
    const std::int64_t ssd = NaiveSsd(r);
    EXPECT_EQ(DotRows(r.ref.data(), r.padded, rows, r.cur.data(), r.step), dot) << width;
    EXPECT_EQ(DotRowsPortable(r.ref.data(), r.padded, rows, r.cur.data(), r.step), dot) << width;
    EXPECT_EQ(SsdRowsMasked(r.ref.data(), r.mask.data(), r.padded, rows, r.cur.data(), r.step), ssd)
        << width;
    EXPECT_EQ(
        SsdRowsMaskedPortable(r.ref.data(), r.mask.data(), r.padded, rows, r.cur.data(), r.step),
        ssd)
        << width;
  }
}

TEST(SsdKernelTest, SquareSumsEqualTheDefinition) {
  std::vector<std::uint8_t> row(77);
  for (std::size_t i = 0; i < row.size(); ++i) row[i] = static_cast<std::uint8_t>(255 - 3 * i);
  std::vector<std::int32_t> acc(row.size(), 5);
  AddSquares(row.data(), static_cast<int>(row.size()), acc.data());
  std::int64_t sum = 0;
  for (std::size_t i = 0; i < row.size(); ++i) {
    EXPECT_EQ(acc[i], 5 + row[i] * row[i]);
    sum += static_cast<std::int64_t>(row[i]) * row[i];
  }
  EXPECT_EQ(SumSquares(row.data(), static_cast<int>(row.size())), sum);
}

}  // namespace
}  // namespace kapfix
