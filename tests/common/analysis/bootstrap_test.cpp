#include "common/analysis/bootstrap.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

// Nine zeros and one 10: a resample's mean is K, the count of 10s drawn, K ~ Binomial(10, 0.1).
// P(K = 0) = 0.349 > 2.5 %, so the lower 2.5 % point is 0; P(K ≤ 2) = 0.930 and
// P(K ≤ 3) = 0.987, so the upper 97.5 % point is 3. 20,000 resamples pin both.
TEST(BootstrapTest, PercentileIntervalMatchesBinomialQuantiles) {
  std::vector<double> values(9, 0.0);
  values.push_back(10.0);
  BootstrapOptions options;
  options.resamples = 20000;
  const ConfidenceInterval ci = BootstrapMean(values, options);
  EXPECT_DOUBLE_EQ(ci.estimate, 1.0);
  EXPECT_DOUBLE_EQ(ci.low, 0.0);
  EXPECT_DOUBLE_EQ(ci.high, 3.0);
}

TEST(BootstrapTest, ConstantValuesGiveAPointInterval) {
  const ConfidenceInterval ci = BootstrapMean({4, 4, 4}, BootstrapOptions{});
  EXPECT_DOUBLE_EQ(ci.low, 4.0);
  EXPECT_DOUBLE_EQ(ci.high, 4.0);
}

TEST(BootstrapTest, SameSeedGivesSameInterval) {
  const std::vector<double> v = {1, 5, 2, 8, 3};
  EXPECT_DOUBLE_EQ(BootstrapMean(v, {}).low, BootstrapMean(v, {}).low);
}

TEST(BootstrapTest, InvalidConfidenceIsRefused) {
  BootstrapOptions options;
  options.confidence = 1.0;
  EXPECT_THROW(BootstrapMean({1, 2}, options), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
