#include "common/selection/fft_score.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>

namespace kapfix {
namespace {

std::vector<double> Sine(int samples, double amplitude, double period, double offset = 0.0) {
  std::vector<double> graph;
  for (int t = 0; t < samples; ++t) {
    graph.push_back(offset + amplitude * std::sin(2.0 * std::numbers::pi * t / period));
  }
  return graph;
}

TEST(FftScoreTest, ConstantGraphScoresZero) {
  EXPECT_NEAR(FftScore(std::vector<double>(100, 7.0)), 0.0, 1e-9);
}

TEST(FftScoreTest, TooShortGraphScoresZero) {
  EXPECT_EQ(FftScore({}), 0.0);
  EXPECT_EQ(FftScore({3.0}), 0.0);
}

TEST(FftScoreTest, PureSineOverWholePeriodsScoresAmplitudeTimesHalfLength) {
  // Not divided by 1000 as in the thesis's tables: 3 px · 400 / 2.
  EXPECT_NEAR(FftScore(Sine(400, 3.0, 40.0)), 600.0, 1e-6);
}

TEST(FftScoreTest, ConstantOffsetIsLeftOut) {
  EXPECT_NEAR(FftScore(Sine(400, 3.0, 40.0, 5.0)), FftScore(Sine(400, 3.0, 40.0)), 1e-6);
}

TEST(FftScoreTest, IncludesTheNyquistBin) {
  // ±1 alternating: all of its energy sits in bin T/2, magnitude T.
  EXPECT_NEAR(FftScore({1, -1, 1, -1}), 4.0, 1e-9);
}

TEST(FftScoreTest, NoiseAddsScore) {
  std::vector<double> noisy = Sine(400, 3.0, 40.0);
  cv::RNG rng(5);
  for (double& v : noisy) v += rng.gaussian(1.0);
  EXPECT_GT(FftScore(noisy), FftScore(Sine(400, 3.0, 40.0)) + 100.0);
}

}  // namespace
}  // namespace kapfix
