#include "common/fixation/patch_roll.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <string>

#include "common/selection/slice_geometry.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

constexpr double kRadPerDeg = std::numbers::pi / 180;
const cv::Size kFrame{640, 480};

// aero1.jpg through a kFrame-sized view, rolled by `roll_rad` (+x towards +y) about the view's
// centre and shifted by `shift` [px]; grey.
cv::Mat View(double roll_rad, cv::Point2d shift) {
  cv::Mat grey;
  cv::cvtColor(testing::RolledView("aero1.jpg", kFrame, roll_rad / kRadPerDeg, shift), grey,
               cv::COLOR_BGR2GRAY);
  return grey;
}

// [px] The patch centre from the frame centre.
cv::Point2d Offset(const cv::Rect& patch) {
  return {patch.x + 0.5 * (patch.width - 1) - 0.5 * (kFrame.width - 1),
          patch.y + 0.5 * (patch.height - 1) - 0.5 * (kFrame.height - 1)};
}

// [px] Where the patch's content goes under the roll and shift (what a perfect match reports).
cv::Point2d PatchDisplacement(double roll_rad, cv::Point2d shift, const cv::Rect& patch) {
  const cv::Point2d r = Offset(patch);
  const double co = std::cos(roll_rad), si = std::sin(roll_rad);
  return {(co - 1) * r.x - si * r.y + shift.x, si * r.x + (co - 1) * r.y + shift.y};
}

class PatchRollTest : public ::testing::TestWithParam<double> {};

TEST_P(PatchRollTest, ReadsTheRollAndDisplacementOfAnOffCentrePatchFromASearchsRoughOne) {
  const double roll = GetParam() * kRadPerDeg;
  const cv::Point2d shift(6, -3);
  const cv::Rect patch = SlicePatch(kFrame, 9, 8, 100);
  const cv::Point2d truth = PatchDisplacement(roll, shift, patch);
  const std::optional<PatchRoll> read =
      ReadPatchRoll(View(0, {0, 0}), patch, View(roll, shift), truth + cv::Point2d(0.8, -0.6), {});
  ASSERT_TRUE(read.has_value());
  EXPECT_NEAR(read->roll_rad / kRadPerDeg, GetParam(), 0.2);
  EXPECT_NEAR(read->displacement.x, truth.x, 0.3) << "refined from 0.8 px off";
  EXPECT_NEAR(read->displacement.y, truth.y, 0.3) << "refined from 0.6 px off";
}

INSTANTIATE_TEST_SUITE_P(Rolls, PatchRollTest, ::testing::Values(-4.0, -2.0, 0.0, 1.0, 3.0));

TEST(PatchRollTest, AnOffCentrePatchHeldUnderRollLeavesTheCentreWhereTheShiftPutIt) {
  const double roll = 3 * kRadPerDeg;
  const cv::Point2d shift(4, 1);
  const cv::Rect patch = SlicePatch(kFrame, 9, 8, 100);
  const cv::Point2d d = PatchDisplacement(roll, shift, patch);
  ASSERT_GT(std::abs(d.x - shift.x), 7) << "the roll moves the patch well away from the centre";
  const cv::Point2d centre = CentreDisplacement(d, roll, Offset(patch));
  EXPECT_NEAR(centre.x, shift.x, 1e-9);
  EXPECT_NEAR(centre.y, shift.y, 1e-9);
}

// SSP may choose the bottom slice, whose patch is clamped against the frame's edge: only the
// patch's inside is compared, so the roll is read there too.
TEST(PatchRollTest, ReadsTheRollOfAPatchOnTheFramesEdge) {
  const double roll = 2 * kRadPerDeg;
  const cv::Point2d shift(3, -2);
  const cv::Rect patch = SlicePatch(kFrame, 9, 9, 100);
  ASSERT_EQ(patch.br().y, kFrame.height) << "the patch touches the bottom edge";
  const cv::Point2d truth = PatchDisplacement(roll, shift, patch);
  const std::optional<PatchRoll> read =
      ReadPatchRoll(View(0, {0, 0}), patch, View(roll, shift), truth + cv::Point2d(0.5, 0.4), {});
  ASSERT_TRUE(read.has_value());
  EXPECT_NEAR(read->roll_rad / kRadPerDeg, 2, 0.2);
  EXPECT_NEAR(read->displacement.x, truth.x, 0.3);
  EXPECT_NEAR(read->displacement.y, truth.y, 0.3);
}

TEST(PatchRollTest, NothingWhenTheDisplacedPatchLeavesTheFrame) {
  const cv::Mat view = View(0, {0, 0});
  const cv::Rect patch = SlicePatch(kFrame, 9, 9, 100);
  EXPECT_FALSE(ReadPatchRoll(view, patch, view, {0, 200}, {}).has_value());
}

TEST(PatchRollTest, IsValidRefusesAnEmptyRangeAStepBeyondItOrNoReduction) {
  PatchRollOptions o;
  std::string error;
  EXPECT_TRUE(o.IsValid(&error)) << error;
  o.max_deg = 0;
  EXPECT_FALSE(o.IsValid(&error));
  o = {};
  o.step_deg = 2 * o.max_deg;
  EXPECT_FALSE(o.IsValid(&error));
  o = {};
  o.reduce = 0;
  EXPECT_FALSE(o.IsValid(&error));
}

}  // namespace
}  // namespace kapfix
