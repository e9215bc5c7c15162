#include "common/sim/world_options.hpp"

#include <gtest/gtest.h>

#include <string>

namespace kapfix {
namespace {

TEST(WorldOptionsTest, NominalLeavesThePlatformAsItIs) {
  SimulatedPlatformOptions platform;
  platform.kite.gusts = true;
  WorldOptions::Nominal().ApplyTo(&platform);
  EXPECT_TRUE(platform.kite.gusts);
  EXPECT_EQ(platform.kite.gust_model, KiteMotionOptions::GustModel::kPeriodic);
  EXPECT_EQ(platform.kite.period_drift, 0.0);
  EXPECT_EQ(platform.camera.roll_max_deg, 0.0);
  EXPECT_EQ(platform.camera.motion_blur_exposure, 0.0);
  EXPECT_EQ(platform.pan.latency_max_frames, 0);
  EXPECT_EQ(platform.frame_drop_rate, 0.0);
  EXPECT_EQ(WorldOptions::Nominal().Describe(), "nominal");
}

TEST(WorldOptionsTest, RealisticTurnsEveryDisturbanceOn) {
  const WorldOptions w = WorldOptions::Realistic();
  ASSERT_TRUE(w.IsValid(nullptr));
  SimulatedPlatformOptions platform;
  w.ApplyTo(&platform);
  EXPECT_EQ(platform.kite.gust_model, KiteMotionOptions::GustModel::kBroadband);
  EXPECT_GT(platform.kite.period_drift, 0.0);
  EXPECT_GT(platform.kite.sway_amplitude_px, 0.0);
  EXPECT_GT(platform.camera.roll_max_deg, 0.0);
  EXPECT_GT(platform.camera.motion_blur_exposure, 0.0);
  EXPECT_GT(platform.camera.exposure_step_max, 0.0);
  EXPECT_GT(platform.pan.latency_max_frames, platform.pan.latency_frames);
  EXPECT_GT(platform.frame_drop_rate, 0.0);
  EXPECT_DOUBLE_EQ(w.calibration_error, 1.3);
  EXPECT_TRUE(platform.IsValid(nullptr));
}

TEST(WorldOptionsTest, EachOutOfRangeValueIsRefusedNamingItsFlag) {
  const auto refused = [](WorldOptions w, const std::string& flag) {
    std::string error;
    EXPECT_FALSE(w.IsValid(&error)) << flag;
    EXPECT_NE(error.find(flag), std::string::npos) << error;
  };
  WorldOptions w;
  w.period_drift = 0.8;
  refused(w, "--period-drift");
  w = {};
  w.roll_deg = -1;
  refused(w, "--roll-deg");
  w = {};
  w.latency_jitter = 11;
  refused(w, "--latency-jitter");
  w = {};
  w.frame_drops = 0.51;
  refused(w, "--frame-drops");
  w = {};
  w.calibration_error = 0.2;
  refused(w, "--calibration-error");
}

TEST(WorldOptionsTest, PresetsAndGustsParseByName) {
  EXPECT_TRUE(WorldOptions::Preset("nominal").has_value());
  EXPECT_EQ(WorldOptions::Preset("realistic")->gusts, WorldOptions::Gusts::kBroadband);
  EXPECT_FALSE(WorldOptions::Preset("stormy").has_value());
  EXPECT_EQ(ParseWorldGusts("off"), WorldOptions::Gusts::kOff);
  EXPECT_EQ(ParseWorldGusts("broadband"), WorldOptions::Gusts::kBroadband);
  EXPECT_FALSE(ParseWorldGusts("gale").has_value());
}

}  // namespace
}  // namespace kapfix
