#include "common/analysis/statistics.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

TEST(StatisticsTest, MeanIsTheAverage) { EXPECT_DOUBLE_EQ(Mean({1, 2, 3, 10}), 4.0); }

TEST(StatisticsTest, StandardDeviationDividesByNMinusOne) {
  // Σ(x − 5)² = 32 over {2, 4, 4, 4, 5, 5, 7, 9}: population σ = 2, sample s = sqrt(32 / 7).
  EXPECT_DOUBLE_EQ(StandardDeviation({2, 4, 4, 4, 5, 5, 7, 9}), std::sqrt(32.0 / 7.0));
}

TEST(StatisticsTest, StandardDeviationIsNotSwampedByALargeOffset) {
  // The naive Σx² − n·mean² loses every digit here; the two-pass form keeps them.
  EXPECT_NEAR(StandardDeviation({1e9 + 1, 1e9 + 2, 1e9 + 3}), 1.0, 1e-9);
}

TEST(StatisticsTest, StandardDeviationRejectsASingleValue) {
  EXPECT_THROW(StandardDeviation({3.0}), std::invalid_argument);
}

TEST(StatisticsTest, MedianOfAnOddCountIsTheMiddleValue) {
  EXPECT_DOUBLE_EQ(Median({9, 1, 5}), 5.0);
}

TEST(StatisticsTest, MedianOfAnEvenCountAveragesTheMiddleTwo) {
  EXPECT_DOUBLE_EQ(Median({4, 1, 3, 2}), 2.5);
}

TEST(StatisticsTest, PercentileInterpolatesBetweenRanks) {
  // Rank 0.9 · (5 − 1) = 3.6 of {10, 20, 30, 40, 50}: 40 + 0.6 · 10.
  EXPECT_DOUBLE_EQ(Percentile({50, 10, 40, 20, 30}, 90), 46.0);
}

TEST(StatisticsTest, PercentileEndsAreTheExtremes) {
  const std::vector<double> v{3, -2, 8};
  EXPECT_DOUBLE_EQ(Percentile(v, 0), -2.0);
  EXPECT_DOUBLE_EQ(Percentile(v, 100), 8.0);
}

TEST(StatisticsTest, PercentileOfAnExactRankNextToAnInfinityIsFinite) {
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_DOUBLE_EQ(Percentile({1, 2, inf}, 50), 2.0);
}

TEST(StatisticsTest, PercentileRejectsPOutsideZeroToHundred) {
  EXPECT_THROW(Percentile({1, 2}, 100.5), std::invalid_argument);
  EXPECT_THROW(Percentile({1, 2}, -1), std::invalid_argument);
}

TEST(StatisticsTest, MedianRejectsNaN) {
  EXPECT_THROW(Median({1, std::nan(""), 3}), std::invalid_argument);
}

TEST(StatisticsTest, RootMeanSquareIgnoresSign) {
  // sqrt((9 + 16 + 9 + 16) / 4) = sqrt(12.5).
  EXPECT_DOUBLE_EQ(RootMeanSquare({3, -4, -3, 4}), std::sqrt(12.5));
}

TEST(StatisticsTest, EveryFunctionRejectsEmptyInput) {
  const std::vector<double> none;
  EXPECT_THROW(Mean(none), std::invalid_argument);
  EXPECT_THROW(StandardDeviation(none), std::invalid_argument);
  EXPECT_THROW(Median(none), std::invalid_argument);
  EXPECT_THROW(Percentile(none, 50), std::invalid_argument);
  EXPECT_THROW(RootMeanSquare(none), std::invalid_argument);
}

TEST(StatisticsTest, EmptyInputMessageNamesTheFunction) {
  try {
    Median({});
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("Median"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace kapfix
