#include "common/evaluation/free_swing_slice.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

#include "common/image/color_channel.hpp"
#include "common/selection/slice_selection.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

std::shared_ptr<const SearchStrategy> Pyr() {
  std::string error;
  return MakeSearchStrategy("pyr", &error);
}

SimulatedPlatformOptions Kite() {
  SimulatedPlatformOptions o;
  o.kite.gusts = true;
  return o;
}

// The free swing's slice is what SSP over the same frames recommends, and the servos held.
TEST(FreeSwingSliceTest, ReturnsSspsRecommendationOverTheSameFrames) {
  const cv::Mat scene = testing::LoadOpenCvPhoto("aero3.jpg");
  FixationOptions fixation;
  SimulatedPlatform platform(scene, Kite());
  const int slice = FreeSwingSlice(platform, fixation, *Pyr(), 40);
  EXPECT_EQ(platform.frame(), 39);  // left on the swing's last frame

  SimulatedPlatform replay(scene, Kite());
  std::vector<cv::Mat> planes;
  for (int k = 0; k < 40; ++k) {
    if (k > 0) replay.Step();
    planes.push_back(ExtractChannel(replay.Capture(), fixation.channel));
  }
  SliceSelectionOptions ssp;
  ssp.search = fixation.search;
  EXPECT_EQ(slice, SelectSlice(planes, *Pyr(), ssp).best_slice);
}

TEST(FreeSwingSliceTest, RefusesASwingOfOneFrame) {
  SimulatedPlatform platform(testing::LoadOpenCvPhoto("aero3.jpg"), Kite());
  EXPECT_THROW(FreeSwingSlice(platform, FixationOptions{}, *Pyr(), 1), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix
