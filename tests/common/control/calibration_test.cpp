#include "common/control/calibration.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

// displacement = slope · move + offset at the thesis's moves.
std::vector<CalibrationSample> Line(double slope, double offset,
                                    const std::vector<double>& moves = CalibrationMoves()) {
  std::vector<CalibrationSample> samples;
  for (const double m : moves) samples.push_back({m, slope * m + offset});
  return samples;
}

// Thesis Table 4.1, first round (D1), 3.5 mm lens: moves −100 … +100 step 10.
std::vector<CalibrationSample> ThesisRoundD1() {
  const std::vector<double> d1 = {-94, -84, -74, -66, -56, -46, -38, -28, -24, -16, -4,
                                  6,   14,  22,  28,  36,  44,  52,  58,  66,  74};
  const std::vector<double> moves = CalibrationMoves();
  std::vector<CalibrationSample> samples;
  for (std::size_t i = 0; i < moves.size(); ++i) samples.push_back({moves[i], d1[i]});
  return samples;
}

TEST(CalibrationTest, ExactLineIsRecovered) {
  const AxisCalibration c = CalibrateAxis(Line(0.5, 3.0));
  EXPECT_NEAR(c.units_per_px_fit, 2.0, 1e-12);
  EXPECT_NEAR(c.offset_px, 3.0, 1e-12);
  EXPECT_NEAR(c.residual_px, 0.0, 1e-12);
}

TEST(CalibrationTest, ExactLineMakesEverySampleAnInlier) {
  // 0.7 and 0.3 are not exact in binary: residuals are rounding noise with a MAD of ~0, which
  // must not turn samples on the line into outliers.
  const AxisCalibration c = CalibrateAxis(Line(0.7, 0.3));
  EXPECT_EQ(c.samples, 21);
  EXPECT_EQ(c.inliers, 21);
}

std::vector<CalibrationSample> LineWithTwoOutliers() {
  std::vector<CalibrationSample> samples = Line(0.8, 0.0);
  samples[3].displacement_px = 80;    // move −70: a mismatch 136 px off the line
  samples[15].displacement_px = -60;  // move 50
  return samples;
}

TEST(CalibrationTest, FitIgnoresGrossOutliers) {
  const AxisCalibration c = CalibrateAxis(LineWithTwoOutliers());
  EXPECT_NEAR(c.units_per_px_fit, 1.25, 1e-12);
  EXPECT_NEAR(c.residual_px, 0.0, 1e-12);
}

TEST(CalibrationTest, OutliersAreNotCountedAsInliers) {
  EXPECT_EQ(CalibrateAxis(LineWithTwoOutliers()).inliers, 19);
}

TEST(CalibrationTest, OutliersMoveTheMedianOfRatiosOnlySlightly) {
  // 19 of 20 ratios are 1.25; the outliers' ratios (−0.875, −0.833) shift the median by less
  // than one rank, i.e. not at all here. A mean of the ratios would move by ~0.2.
  EXPECT_NEAR(CalibrateAxis(LineWithTwoOutliers()).units_per_px_median, 1.25, 1e-12);
}

// Positive moves only, with the −4 px offset Table 4.1 shows at a zero move.
std::vector<CalibrationSample> OffsetLine() {
  return Line(0.8, -4.0, {10, 20, 30, 40, 50, 60, 70, 80, 90, 100});
}

TEST(CalibrationTest, FitAbsorbsAnOffset) {
  const AxisCalibration c = CalibrateAxis(OffsetLine());
  EXPECT_NEAR(c.units_per_px_fit, 1.25, 1e-12);
  EXPECT_NEAR(c.offset_px, -4.0, 1e-12);
}

TEST(CalibrationTest, OffsetBiasesTheMedianOfRatios) {
  // Ratios m / (0.8 m − 4) all exceed 1.25; the middle two (m = 50, 60) are 50/36 and 60/44,
  // median 1.376.
  EXPECT_NEAR(CalibrateAxis(OffsetLine()).units_per_px_median, 0.5 * (50.0 / 36 + 60.0 / 44),
              1e-12);
}

TEST(CalibrationTest, ThesisRoundD1FitsFiveSixthsPixelPerUnit) {
  // Computed independently (python3 stdlib over the 210 pairwise slopes of D1): the median
  // pairwise slope is exactly 5/6 px per unit (e.g. (74 − 24) / 60 = 50/60; the 105th and
  // 106th sorted slopes are both 0.8333), so 1.2 units per px, the median intercept −6 px.
  // The brief's "≈ 0.84" is this figure; the ends of the table (±100 → −94, 74) give 0.84.
  const AxisCalibration c = CalibrateAxis(ThesisRoundD1());
  EXPECT_NEAR(1.0 / c.units_per_px_fit, 5.0 / 6.0, 1e-9);
  EXPECT_NEAR(c.offset_px, -6.0, 1e-9);
}

TEST(CalibrationTest, ThesisRoundD1KeepsEverySampleWithAFewPixelsResidual) {
  // Residuals of the 5/6 line reach 4.7 px; 1.4826 · MAD = 2.47 px, 3σ = 7.4 px keeps them all.
  // RMS of the 21 residuals: 2.379 px (python3, same data).
  const AxisCalibration c = CalibrateAxis(ThesisRoundD1());
  EXPECT_EQ(c.inliers, 21);
  EXPECT_NEAR(c.residual_px, 2.3794, 1e-3);
}

TEST(CalibrationTest, ThesisRoundD1MedianOfRatiosMatchesTheTable) {
  // 20 ratios (the zero move is skipped); the middle two are 1.0870 (−50 / −46) and 1.3462
  // (70 / 52), median 1.2166 — within the 1.1–1.4 the table's C columns span, and above the
  // fit's 1.2 because the −4…−6 px offset inflates the positive moves' ratios.
  const double median = CalibrateAxis(ThesisRoundD1()).units_per_px_median;
  EXPECT_NEAR(median, 0.5 * (50.0 / 46 + 70.0 / 52), 1e-12);
  EXPECT_GT(median, 1.1);
  EXPECT_LT(median, 1.4);
}

TEST(CalibrationTest, RatioMedianSkipsDisplacementsBelowOnePixel) {
  // Ratios 25 and 22.2 from sub-pixel displacements would make the median 12.1.
  const AxisCalibration c = CalibrateAxis({{10, 0.4}, {20, 0.9}, {40, 20}, {60, 30}});
  EXPECT_DOUBLE_EQ(c.units_per_px_median, 2.0);
}

TEST(CalibrationTest, RatioMedianSkipsTheZeroMove) {
  // With 0 / 5 = 0 included the median would be 1.5.
  const AxisCalibration c = CalibrateAxis({{0, 5}, {10, 5}, {20, 10}});
  EXPECT_DOUBLE_EQ(c.units_per_px_median, 2.0);
}

TEST(CalibrationTest, ThesisCountingEntersZeroMovesAsZeroRatios) {
  // Ratios 2, 2, 2 and two zero moves: sorted 0 0 2 2 2, median 2; with three zero moves the
  // median of 0 0 0 2 2 2 is 1 (the robust rule stays at 2).
  const AxisCalibration c = CalibrateAxis({{0, 5}, {0, -5}, {0, 1}, {10, 5}, {20, 10}, {40, 20}});
  EXPECT_DOUBLE_EQ(c.units_per_px_thesis, 1.0);
  EXPECT_DOUBLE_EQ(c.units_per_px_median, 2.0);
}

TEST(CalibrationTest, RejectsASingleSample) {
  EXPECT_THROW(CalibrateAxis({{10, 8}}), std::invalid_argument);
}

TEST(CalibrationTest, RejectsSamplesThatAllShareOneMove) {
  EXPECT_THROW(CalibrateAxis({{10, 8}, {10, 9}, {10, 7}}), std::invalid_argument);
}

TEST(CalibrationTest, RejectsAZeroSlopeNamingIt) {
  try {
    CalibrateAxis(Line(0.0, 2.0));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("zero slope"), std::string::npos) << e.what();
  }
}

TEST(CalibrationTest, RejectsWhenNoSampleMovedAPixel) {
  EXPECT_THROW(CalibrateAxis({{10, 0.1}, {20, 0.2}}), std::invalid_argument);
}

TEST(CalibrationMovesTest, ThesisMovesRunFromMinusToPlusHundredInTens) {
  const std::vector<double> moves = CalibrationMoves();
  ASSERT_EQ(moves.size(), 21u);
  for (std::size_t i = 0; i < moves.size(); ++i) {
    EXPECT_DOUBLE_EQ(moves[i], -100.0 + 10.0 * static_cast<double>(i));
  }
}

TEST(CalibrationMovesTest, CustomSpanAndStep) {
  EXPECT_EQ(CalibrationMoves(30, 15), (std::vector<double>{-30, -15, 0, 15, 30}));
}

TEST(CalibrationMovesTest, RejectsANonPositiveStep) {
  EXPECT_THROW(CalibrationMoves(100, 0), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
