// Settings commands applied to the AgentConfig, and the config shown back as AgentState: a
// partial update keeps what it does not name, an invalid value changes nothing.
#include "agent/commands/settings_messages.hpp"

#include <gtest/gtest.h>

#include <algorithm>

namespace kapfix::agent {
namespace {

const LensProfile* FindLens(const AgentConfig& config, const std::string& name) {
  const auto it = std::find_if(config.lenses.begin(), config.lenses.end(),
                               [&](const LensProfile& p) { return p.name == name; });
  return it == config.lenses.end() ? nullptr : &*it;
}

TEST(SettingsMessagesTest, GainsUpdateChangesOnlyTheGivenFields) {
  AgentConfig config;
  const kapfix::v1::Gains before = config.gains;
  kapfix::v1::Command command;
  command.mutable_set_gains()->set_p(0.25F);
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(command, &config, &error)) << error;
  EXPECT_DOUBLE_EQ(config.gains.p(), 0.25);
  EXPECT_EQ(config.gains.controller(), before.controller());
  EXPECT_DOUBLE_EQ(config.gains.i(), before.i());
  EXPECT_DOUBLE_EQ(config.gains.d(), before.d());
  EXPECT_DOUBLE_EQ(config.gains.dead_band_px(), before.dead_band_px());
  EXPECT_DOUBLE_EQ(config.gains.rate_limit_deg_per_s(), before.rate_limit_deg_per_s());
}

TEST(SettingsMessagesTest, SearchUpdateChangesOnlyTheGivenFields) {
  AgentConfig config;
  const SearchConfig before = config.search;
  kapfix::v1::Command command;
  command.mutable_set_search()->set_strategy("h23");
  command.mutable_set_search()->set_slice_count(5);
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(command, &config, &error)) << error;
  EXPECT_EQ(config.search.strategy, "h23");
  EXPECT_EQ(config.search.slices, 5);
  EXPECT_EQ(config.search.patch_px, before.patch_px);
  EXPECT_EQ(config.search.range_px, before.range_px);
  EXPECT_EQ(config.search.axis, before.axis);
  EXPECT_EQ(config.search.subpixel, before.subpixel);
  EXPECT_EQ(config.search.sampling.kind, before.sampling.kind);
  EXPECT_EQ(config.search.channel, before.channel);
  EXPECT_EQ(config.search.score, before.score);
}

TEST(SettingsMessagesTest, VideoUpdateChangesOnlyTheGivenFields) {
  AgentConfig config;
  kapfix::v1::Command command;
  command.mutable_set_video()->set_fps(5);
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(command, &config, &error)) << error;
  EXPECT_FLOAT_EQ(config.video.fps(), 5);
  EXPECT_EQ(config.video.jpeg_quality(), AgentConfig{}.video.jpeg_quality());
  EXPECT_FLOAT_EQ(config.video.scale(), AgentConfig{}.video.scale());
}

TEST(SettingsMessagesTest, InvalidValueIsRefusedNamingTheFieldAndChangesNothing) {
  AgentConfig config;
  kapfix::v1::Command command;
  command.mutable_set_gains()->set_p(0.5F);
  command.mutable_set_gains()->set_i(50.0F);  // gains are 0…10
  std::string error;
  EXPECT_FALSE(ApplySettingsCommand(command, &config, &error));
  EXPECT_NE(error.find("gains.i"), std::string::npos) << error;
  EXPECT_DOUBLE_EQ(config.gains.p(), AgentConfig{}.gains.p());  // the valid part not applied
  EXPECT_DOUBLE_EQ(config.gains.i(), AgentConfig{}.gains.i());
}

TEST(SettingsMessagesTest, UnknownStrategyIsRefusedNamingTheField) {
  AgentConfig config;
  kapfix::v1::Command command;
  command.mutable_set_search()->set_strategy("fastest");
  std::string error;
  EXPECT_FALSE(ApplySettingsCommand(command, &config, &error));
  EXPECT_NE(error.find("search.strategy"), std::string::npos) << error;
  EXPECT_EQ(config.search.strategy, SearchConfig{}.strategy);
}

TEST(SettingsMessagesTest, NonSettingsCommandIsRefused) {
  AgentConfig config;
  kapfix::v1::Command command;
  command.mutable_take_photo()->set_note("x");
  std::string error;
  EXPECT_FALSE(ApplySettingsCommand(command, &config, &error));
  EXPECT_FALSE(error.empty());
}

TEST(SettingsMessagesTest, LensByOpticsCreatesTheProfileAndSelectsIt) {
  AgentConfig config;
  kapfix::v1::Command command;
  kapfix::v1::LensProfile* lens = command.mutable_set_lens();
  lens->set_name("6mm");
  lens->set_focal_length_mm(6.0F);
  lens->set_pixel_pitch_um(10.6F);
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(command, &config, &error)) << error;
  EXPECT_EQ(config.lens, "6mm");
  const LensProfile* profile = FindLens(config, "6mm");
  ASSERT_NE(profile, nullptr);
  EXPECT_FLOAT_EQ(static_cast<float>(profile->focal_mm), 6.0F);
  EXPECT_FLOAT_EQ(static_cast<float>(profile->pixel_pitch_um), 10.6F);
  EXPECT_NE(FindLens(config, "default"), nullptr);  // the others stay
}

TEST(SettingsMessagesTest, LensProfilesStopAtTheirBoundAndTheRefusalSaysSo) {
  AgentConfig config;
  std::string error;
  for (std::size_t i = config.lenses.size(); i <= AgentConfig::kMaxLensProfiles; ++i) {
    kapfix::v1::Command command;
    kapfix::v1::LensProfile* lens = command.mutable_set_lens();
    lens->set_name("lens-" + std::to_string(i));
    lens->set_focal_length_mm(6.0F);
    lens->set_pixel_pitch_um(10.6F);
    const bool applied = ApplySettingsCommand(command, &config, &error);
    if (i < AgentConfig::kMaxLensProfiles) {
      ASSERT_TRUE(applied) << i << ": " << error;
    } else {
      EXPECT_FALSE(applied);
      EXPECT_NE(error.find("at most 64"), std::string::npos) << error;
    }
  }
  EXPECT_EQ(config.lenses.size(), AgentConfig::kMaxLensProfiles);  // the refused one is not kept
}

TEST(SettingsMessagesTest, LensByOpticsReplacesTheProfilesDegreesPerPixel) {
  AgentConfig config;  // "default": 0.1 deg/px given directly
  kapfix::v1::Command command;
  command.mutable_set_lens()->set_name("default");
  command.mutable_set_lens()->set_focal_length_mm(3.5F);
  command.mutable_set_lens()->set_pixel_pitch_um(10.6F);
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(command, &config, &error)) << error;
  ASSERT_EQ(config.lenses.size(), 1u);
  EXPECT_EQ(config.lenses[0].deg_per_px_pan, 0);
  EXPECT_NEAR(config.active_lens().DegPerPxPan(), 0.1735, 0.001);  // atan(10.6 µm / 3.5 mm)
}

TEST(SettingsMessagesTest, LensByNameSwitchesToAStoredProfile) {
  AgentConfig config;
  config.lenses.push_back(LensProfile{.name = "6mm", .focal_mm = 6, .pixel_pitch_um = 10.6});
  kapfix::v1::Command command;
  command.mutable_set_lens()->set_name("6mm");
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(command, &config, &error)) << error;
  EXPECT_EQ(config.lens, "6mm");
  EXPECT_DOUBLE_EQ(FindLens(config, "6mm")->focal_mm, 6);
}

TEST(SettingsMessagesTest, UnknownLensWithoutOpticsIsRefused) {
  AgentConfig config;
  kapfix::v1::Command command;
  command.mutable_set_lens()->set_name("fisheye");
  std::string error;
  EXPECT_FALSE(ApplySettingsCommand(command, &config, &error));
  EXPECT_NE(error.find("fisheye"), std::string::npos) << error;
  EXPECT_EQ(config.lens, "default");
  EXPECT_EQ(config.lenses.size(), 1u);
}

TEST(SettingsMessagesTest, AutoExposureClearsTheExposureTime) {
  AgentConfig config;
  config.camera.settings.set_exposure_us(2000);
  kapfix::v1::Command command;
  command.mutable_set_camera()->set_auto_exposure(true);
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(command, &config, &error)) << error;
  EXPECT_FALSE(config.camera.settings.has_exposure_us());
}

TEST(SettingsMessagesTest, AFixedExposureTurnsAutomaticExposureOff) {
  AgentConfig config;
  ASSERT_TRUE(config.camera.settings.auto_exposure()) << "the agent starts on automatic exposure";
  kapfix::v1::Command command;
  command.mutable_set_camera()->set_exposure_us(2000);
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(command, &config, &error)) << error;
  EXPECT_FLOAT_EQ(config.camera.settings.exposure_us(), 2000);
  kapfix::v1::AgentState state;
  FillSettings(config, &state);
  EXPECT_FALSE(state.camera().auto_exposure());
  EXPECT_FLOAT_EQ(state.camera().exposure_us(), 2000);
  EXPECT_FLOAT_EQ(state.camera().gain_db(), 0) << "a gain left to the camera reads 0";
}

TEST(SettingsMessagesTest, AutomaticExposureSwitchedOffAloneKeepsIt) {
  AgentConfig config;
  kapfix::v1::Command command;
  command.mutable_set_camera()->set_auto_exposure(false);
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(command, &config, &error)) << error;
  EXPECT_TRUE(config.camera.settings.auto_exposure());
}

TEST(SettingsMessagesTest, PhotoIntervalIsApplied) {
  AgentConfig config;
  kapfix::v1::Command command;
  command.mutable_set_photo()->set_interval_s(30);
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(command, &config, &error)) << error;
  EXPECT_FLOAT_EQ(config.photo.interval_s(), 30.0F);
}

TEST(SettingsMessagesTest, FillSettingsReflectsTheConfig) {
  AgentConfig config;
  config.gains.set_controller(kapfix::v1::CONTROLLER_KIND_PID);
  config.gains.set_p(0.5F);
  config.search.strategy = "h21";
  config.search.patch_px = 50;
  config.search.slices = 7;
  config.search.axis = SearchAxis::kY;
  config.camera.settings.set_gain_db(6);
  config.camera.settings.set_exposure_us(1500);
  config.camera.settings.clear_auto_exposure();
  config.camera.width = 800;
  config.camera.height = 600;
  config.photo.set_interval_s(10);
  config.video.set_fps(15);
  config.video.set_jpeg_quality(70);
  kapfix::v1::AgentState state;
  FillSettings(config, &state);
  EXPECT_EQ(state.gains().controller(), kapfix::v1::CONTROLLER_KIND_PID);
  EXPECT_FLOAT_EQ(state.gains().p(), 0.5F);
  EXPECT_EQ(state.search().strategy(), "h21");
  EXPECT_EQ(state.search().patch_size_px(), 50u);
  EXPECT_EQ(state.search().slice_count(), 7u);
  EXPECT_EQ(state.search().axis(), kapfix::v1::AXIS_Y);
  EXPECT_FLOAT_EQ(state.camera().gain_db(), 6.0F);
  EXPECT_FLOAT_EQ(state.camera().exposure_us(), 1500.0F);
  EXPECT_FALSE(state.camera().auto_exposure());
  EXPECT_EQ(state.lens().name(), "default");
  EXPECT_FLOAT_EQ(state.photo().interval_s(), 10.0F);
  EXPECT_FLOAT_EQ(state.video().fps(), 15.0F);
  EXPECT_EQ(state.video().jpeg_quality(), 70u);
  EXPECT_EQ(state.frame_width_px(), 800u);
  EXPECT_EQ(state.frame_height_px(), 600u);
}

TEST(SettingsMessagesTest, FilledSettingsAppliedBackChangeNothing) {
  AgentConfig config;
  config.search.strategy = "h23";
  config.gains.set_p(0.5F);
  kapfix::v1::AgentState state;
  FillSettings(config, &state);
  AgentConfig copy;
  kapfix::v1::Command gains;
  *gains.mutable_set_gains() = state.gains();
  kapfix::v1::Command search;
  *search.mutable_set_search() = state.search();
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(gains, &copy, &error)) << error;
  ASSERT_TRUE(ApplySettingsCommand(search, &copy, &error)) << error;
  EXPECT_EQ(copy.search.strategy, "h23");
  EXPECT_DOUBLE_EQ(copy.gains.p(), 0.5);
  EXPECT_EQ(copy.search.patch_px, config.search.patch_px);
  EXPECT_EQ(copy.search.sampling.kind, config.search.sampling.kind);
}

// Issue 13: set_photo changes the shutter settings it names and AgentState.photo shows them;
// the state's settings applied back change nothing.
TEST(SettingsMessagesTest, SetPhotoRoundTripsThroughTheState) {
  AgentConfig config;
  kapfix::v1::Command command;
  command.mutable_set_photo()->set_shutter(kapfix::v1::SHUTTER_BEST_PHASE);
  command.mutable_set_photo()->set_window_s(2.5F);
  command.mutable_set_photo()->set_exposure_ms(4.0F);
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(command, &config, &error)) << error;
  EXPECT_EQ(config.photo.shutter(), kapfix::v1::SHUTTER_BEST_PHASE);
  EXPECT_FLOAT_EQ(config.photo.window_s(), 2.5F);
  EXPECT_FLOAT_EQ(config.photo.window_cap_s(), 10.0F);  // not named: kept
  EXPECT_FLOAT_EQ(config.photo.exposure_ms(), 4.0F);
  kapfix::v1::AgentState state;
  FillSettings(config, &state);
  EXPECT_EQ(state.photo().shutter(), kapfix::v1::SHUTTER_BEST_PHASE);
  EXPECT_FLOAT_EQ(state.photo().window_s(), 2.5F);
  EXPECT_FLOAT_EQ(state.photo().window_cap_s(), 10.0F);
  EXPECT_FLOAT_EQ(state.photo().exposure_ms(), 4.0F);
  EXPECT_EQ(state.photo().camera(), kapfix::v1::PHOTO_CAMERA_AGENT);
  AgentConfig copy;
  kapfix::v1::Command back;
  *back.mutable_set_photo() = state.photo();
  ASSERT_TRUE(ApplySettingsCommand(back, &copy, &error)) << error;
  EXPECT_EQ(copy.photo.shutter(), kapfix::v1::SHUTTER_BEST_PHASE);
  EXPECT_FLOAT_EQ(copy.photo.window_s(), 2.5F);
  EXPECT_FLOAT_EQ(copy.photo.exposure_ms(), 4.0F);
}

// An enum at *_UNSPECIFIED means "unchanged" even where the field has presence.
TEST(SettingsMessagesTest, AnUnspecifiedShutterKeepsTheHeldOne) {
  AgentConfig config;
  config.photo.set_shutter(kapfix::v1::SHUTTER_BEST_PHASE);
  kapfix::v1::Command command;
  command.mutable_set_photo()->set_shutter(kapfix::v1::SHUTTER_UNSPECIFIED);
  command.mutable_set_photo()->set_window_s(2.0F);
  std::string error;
  ASSERT_TRUE(ApplySettingsCommand(command, &config, &error)) << error;
  EXPECT_EQ(config.photo.shutter(), kapfix::v1::SHUTTER_BEST_PHASE);
  EXPECT_FLOAT_EQ(config.photo.window_s(), 2.0F);
}

TEST(SettingsMessagesTest, SetPhotoWindowBeyondTheCapChangesNothing) {
  AgentConfig config;
  kapfix::v1::Command command;
  command.mutable_set_photo()->set_shutter(kapfix::v1::SHUTTER_BEST_PHASE);
  command.mutable_set_photo()->set_window_cap_s(2.0F);
  command.mutable_set_photo()->set_window_s(3.0F);
  std::string error;
  EXPECT_FALSE(ApplySettingsCommand(command, &config, &error));
  EXPECT_NE(error.find("longer than its cap"), std::string::npos) << error;
  EXPECT_EQ(config.photo.shutter(), kapfix::v1::SHUTTER_INTERVAL);
  EXPECT_FLOAT_EQ(config.photo.window_cap_s(), 10.0F);
}

}  // namespace
}  // namespace kapfix::agent
