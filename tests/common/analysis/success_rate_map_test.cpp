#include "common/analysis/success_rate_map.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

ErrorSurface MakeSurface(int range, const std::function<double(int, int)>& f) {
  ErrorSurface surface;
  surface.range = range;
  surface.distance = cv::Mat(2 * range + 1, 2 * range + 1, CV_64F);
  for (int dy = -range; dy <= range; ++dy) {
    for (int dx = -range; dx <= range; ++dx) {
      surface.distance.at<double>(range + dy, range + dx) = f(dx, dy);
    }
  }
  return surface;
}

ErrorSurface Bowl(int range = 10) {
  return MakeSurface(range, [](int x, int y) { return double(x * x + y * y); });
}

// Global basin at (−5, 0), a shallower local one (bottom 10 instead of 0) at (5, 0).
ErrorSurface TwoBasins() {
  return MakeSurface(10, [](int x, int y) {
    return std::min(double((x + 5) * (x + 5) + y * y), double((x - 5) * (x - 5) + y * y) + 10);
  });
}

// Per axis a cone 8|u| out to |u| = 8, then a shelf rising only 0.4 per cell to the edge.
// Nearly all central differences are 8, so the slope scale is 8 and the shelf's normalised
// slope 0.05: gain 1 rounds it to no move, gain 10 to one cell. (An exactly flat shelf has no
// slope for any gain to amplify.) The cone moves one cell per step at gain 1, so only the
// shelf needs the escalation.
double ConeWithShelf(int u) {
  const int a = std::abs(u);
  return a <= 8 ? 8.0 * a : 64.0 + 0.4 * (a - 8);
}
ErrorSurface ShelfSurface() {
  return MakeSurface(10, [](int x, int y) { return ConeWithShelf(x) + ConeWithShelf(y); });
}

DescentOptions NoEscalation() {
  DescentOptions options;
  options.max_gain = options.initial_gain;
  return options;
}

bool Succeeded(const SuccessRateMap& map, int range, int x, int y) {
  return map.success.at<std::uint8_t>(range + y, range + x) == 1;
}

TEST(DescentOptionsTest, DefaultsAreValid) {
  std::string error;
  EXPECT_TRUE(DescentOptions{}.IsValid(&error)) << error;
}

TEST(DescentOptionsTest, MaxGainBelowInitialGainIsInvalid) {
  DescentOptions options;
  options.max_gain = 0.5;
  std::string error;
  EXPECT_FALSE(options.IsValid(&error));
  EXPECT_NE(error.find("max_gain"), std::string::npos) << error;
}

TEST(DescentOptionsTest, ZeroGainStepIsInvalid) {
  DescentOptions options;
  options.gain_step = 0.0;
  EXPECT_FALSE(options.IsValid(nullptr));
}

TEST(DescentTest, SlopeScaleIsTheMedianNonZeroCentralDifference) {
  // Central differences are 2|u| for |u| ≤ 9 on a range-10 bowl; the non-zero ones, 2 … 18 in
  // equal numbers, have median 10.
  EXPECT_DOUBLE_EQ(SurfaceSlopeScale(Bowl()), 10.0);
}

TEST(DescentTest, ReachesTheBottomOfABowlAtALocalMinimum) {
  const ErrorSurface bowl = Bowl();
  const DescentResult r = Descend(bowl, {10, -10}, SurfaceSlopeScale(bowl), DescentOptions{});
  EXPECT_EQ(r.end, cv::Point(0, 0));
  EXPECT_EQ(r.stop, DescentStop::kLocalMinimum);
}

TEST(DescentTest, CountsMovesNotGainRaises) {
  // Bowl x² + y², scale 10 (see above), from (3, 0): normalised slopes 0.6 → one cell; at x = 2
  // 0.4 rounds to 0, gain 2 moves one cell; at x = 1 0.2 needs gain 3. Three moves, three raises.
  const ErrorSurface bowl = Bowl();
  EXPECT_EQ(Descend(bowl, {3, 0}, SurfaceSlopeScale(bowl), DescentOptions{}).steps, 3);
}

TEST(DescentTest, StopsAtTheStepLimit) {
  DescentOptions options;
  options.max_steps = 1;
  const ErrorSurface bowl = Bowl();
  const DescentResult r = Descend(bowl, {10, 10}, SurfaceSlopeScale(bowl), options);
  EXPECT_EQ(r.stop, DescentStop::kStepLimit);
  EXPECT_EQ(r.steps, 1);
}

TEST(DescentTest, GainEscalationMovesOffAShallowShelf) {
  const ErrorSurface shelf = ShelfSurface();
  const DescentResult r = Descend(shelf, {10, 0}, SurfaceSlopeScale(shelf), DescentOptions{});
  EXPECT_EQ(r.end, cv::Point(0, 0));
}

TEST(DescentTest, StopsOnAShallowShelfWhenTheGainCannotRise) {
  const ErrorSurface shelf = ShelfSurface();
  const DescentResult r = Descend(shelf, {10, 0}, SurfaceSlopeScale(shelf), NoEscalation());
  EXPECT_EQ(r.stop, DescentStop::kGainExhausted);
  EXPECT_EQ(r.end, cv::Point(10, 0));
}

TEST(DescentTest, InvalidCellsAreWalls) {
  // A bowl centred on (0, 0) whose cells right of x = −3 are invalid: the lowest reachable
  // cell is (−3, 0), a local minimum once the invalid neighbour is ignored.
  ErrorSurface s = MakeSurface(10, [](int x, int y) {
    return x > -3 ? std::numeric_limits<double>::quiet_NaN() : double(x * x + y * y);
  });
  const DescentResult r = Descend(s, {-10, 6}, SurfaceSlopeScale(s), DescentOptions{});
  EXPECT_EQ(r.end, cv::Point(-3, 0));
  EXPECT_EQ(r.stop, DescentStop::kLocalMinimum);
}

TEST(DescentTest, RejectsAnInvalidStart) {
  ErrorSurface s = Bowl(3);
  s.distance.at<double>(3, 3) = std::nan("");
  EXPECT_THROW(Descend(s, {0, 0}, 1.0, DescentOptions{}), std::invalid_argument);
}

TEST(SuccessRateMapTest, BowlSucceedsFromEveryStart) {
  const SuccessRateMap map = ComputeSuccessRateMap(Bowl(), DescentOptions{});
  EXPECT_EQ(map.starts, 21 * 21);
  EXPECT_DOUBLE_EQ(map.success_pct, 100.0);
}

TEST(SuccessRateMapTest, LocalBasinStartsFail) {
  const SuccessRateMap map = ComputeSuccessRateMap(TwoBasins(), DescentOptions{});
  EXPECT_FALSE(Succeeded(map, 10, 5, 0));
  EXPECT_FALSE(Succeeded(map, 10, 6, 1));
  EXPECT_TRUE(Succeeded(map, 10, -5, 0));
  EXPECT_TRUE(Succeeded(map, 10, -6, 1));
}

TEST(SuccessRateMapTest, TwoBasinsGivePartialSuccess) {
  const SuccessRateMap map = ComputeSuccessRateMap(TwoBasins(), DescentOptions{});
  EXPECT_GT(map.success_pct, 20.0);
  EXPECT_LT(map.success_pct, 80.0);
}

TEST(SuccessRateMapTest, GainEscalationMakesTheShelfSucceed) {
  EXPECT_DOUBLE_EQ(ComputeSuccessRateMap(ShelfSurface(), DescentOptions{}).success_pct, 100.0);
}

TEST(SuccessRateMapTest, WithoutEscalationOnlyStartsOffTheShelfSucceed) {
  // Off the shelf: |x| ≤ 8 and |y| ≤ 8, 17 × 17 of the 21 × 21 starts.
  const SuccessRateMap map = ComputeSuccessRateMap(ShelfSurface(), NoEscalation());
  EXPECT_DOUBLE_EQ(map.success_pct, 100.0 * 17 * 17 / (21 * 21));
  EXPECT_FALSE(Succeeded(map, 10, 9, 0));
  EXPECT_TRUE(Succeeded(map, 10, 8, 8));
}

TEST(SuccessRateMapTest, InvalidCellsAreNeitherStartsNorSuccesses) {
  ErrorSurface s = Bowl();
  s.distance.row(0).setTo(std::numeric_limits<double>::quiet_NaN());
  const SuccessRateMap map = ComputeSuccessRateMap(s, DescentOptions{});
  EXPECT_EQ(map.starts, 20 * 21);
  EXPECT_EQ(cv::countNonZero(map.success.row(0)), 0);
  EXPECT_DOUBLE_EQ(map.success_pct, 100.0);
}

TEST(SuccessRateMapTest, SuccessMapHasTheSurfaceGeometry) {
  const SuccessRateMap map = ComputeSuccessRateMap(Bowl(4), DescentOptions{});
  EXPECT_EQ(map.success.type(), CV_8UC1);
  EXPECT_EQ(map.success.size(), cv::Size(9, 9));
}

TEST(SuccessRateMapTest, StepsHistogramCountsEverySuccessfulStartOnce) {
  const SuccessRateMap map = ComputeSuccessRateMap(TwoBasins(), DescentOptions{});
  int total = 0;
  for (const auto& [steps, count] : map.steps_histogram) total += count;
  EXPECT_EQ(total, cv::countNonZero(map.success));
  EXPECT_EQ(map.steps_histogram.at(0), 1);  // only the minimum itself needs no move
}

TEST(SuccessRateMapTest, MapDoesNotDependOnTheSurfaceUnits) {
  ErrorSurface scaled = TwoBasins();
  scaled.distance *= 1000.0;
  const cv::Mat a = ComputeSuccessRateMap(TwoBasins(), DescentOptions{}).success;
  const cv::Mat b = ComputeSuccessRateMap(scaled, DescentOptions{}).success;
  EXPECT_EQ(cv::countNonZero(a != b), 0);
}

TEST(SuccessRateMapTest, ReportsProgressOncePerRow) {
  std::vector<int> done;
  ComputeSuccessRateMap(Bowl(3), DescentOptions{}, [&](int d, int total) {
    EXPECT_EQ(total, 7);
    done.push_back(d);
  });
  EXPECT_EQ(done, (std::vector<int>{1, 2, 3, 4, 5, 6, 7}));
}

TEST(SuccessRateMapTest, RejectsASurfaceWithoutValidCells) {
  ErrorSurface s = Bowl(2);
  s.distance.setTo(std::numeric_limits<double>::quiet_NaN());
  EXPECT_THROW(ComputeSuccessRateMap(s, DescentOptions{}), std::invalid_argument);
}

TEST(SuccessRateMapTest, RejectsInvalidOptions) {
  EXPECT_THROW(ComputeSuccessRateMap(Bowl(2), DescentOptions{.max_steps = -1}),
               std::invalid_argument);
}

}  // namespace
}  // namespace kapfix

namespace kapfix {
namespace {

// Tables 3.1 and 3.2 as printed: 14,600 pixels for static sampling, 2,500 for random.
constexpr int kPrintedStaticPixels = 14600;
constexpr int kPrintedRandomPixels = 2500;

TEST(ThesisTable32SamplingTest, TheProgramsCountsAreTheThesissPrintedOnes) {
  EXPECT_EQ(kThesisStaticPixels, kPrintedStaticPixels);
  EXPECT_EQ(kThesisRandomPixels, kPrintedRandomPixels);
}

TEST(ThesisTable32SamplingTest, StaticReachesTheThesisCountOnTheSmallestPatch) {
  const ThesisSurfaceSampling s = ThesisTable32Sampling(SamplingKind::kStatic, 1);
  EXPECT_GE(s.sampled_pixels, kPrintedStaticPixels);
  // One pixel less on the side would fall short: the patch is the smallest that reaches it.
  SamplingOptions smaller;
  smaller.kind = SamplingKind::kStatic;
  EXPECT_LT(
      static_cast<int>(MakeSamplingPattern({s.patch_side - 1, s.patch_side - 1}, smaller).size()),
      kPrintedStaticPixels);
  // Within 1 % of 14,600 (Table 3.1 and 3.2 print it rounded).
  EXPECT_LT(s.sampled_pixels, kPrintedStaticPixels * 1.01);
}

TEST(ThesisTable32SamplingTest, RandomDrawsExactly2500PixelsOnTheSamePatch) {
  const ThesisSurfaceSampling r = ThesisTable32Sampling(SamplingKind::kRandom, 3);
  EXPECT_EQ(r.sampled_pixels, kPrintedRandomPixels);
  EXPECT_EQ(r.patch_side, ThesisTable32Sampling(SamplingKind::kStatic, 3).patch_side);
}

}  // namespace
}  // namespace kapfix
