#include "common/analysis/ranks.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

TEST(RankStatisticsTest, TiedValuesShareTheirAverageRank) {
  // Sorted: 1 (rank 1), 2 2 2 (ranks 2–4 → 3), 5 (rank 5), 7 7 (ranks 6–7 → 6.5).
  const Ranking r = AverageRanks({7, 2, 1, 2, 5, 7, 2});
  EXPECT_EQ(r.ranks, (std::vector<double>{6.5, 3, 1, 3, 5, 6.5, 3}));
}

TEST(RankStatisticsTest, TieSumAddsTCubedMinusTPerTieGroup) {
  // A triple (27 − 3 = 24) and a pair (8 − 2 = 6).
  EXPECT_DOUBLE_EQ(AverageRanks({7, 2, 1, 2, 5, 7, 2}).tie_sum, 30.0);
}

TEST(RankStatisticsTest, RankingRejectsNaN) {
  EXPECT_THROW(AverageRanks({1, std::nan("")}), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
