#include "link/setting_key.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

namespace kapfix::link {
namespace {

using ::testing::HasSubstr;

TEST(SettingKeyTest, GainKeySetsThatGainOnly) {
  const auto command = MakeSetCommand("p", "0.5", nullptr);
  ASSERT_TRUE(command.has_value());
  ASSERT_TRUE(command->has_set_gains());
  EXPECT_FLOAT_EQ(command->set_gains().p(), 0.5F);
  EXPECT_FALSE(command->set_gains().has_i());
}

TEST(SettingKeyTest, EveryKeyBuildsACommand) {
  // One readable value per kind of key.
  for (const SettingKey& key : SettingKeys()) {
    bool built = false;
    for (const char* value :
         {"1", "on", "x", "p", "all", "green", "dc", "h23", "6mm", "interval", "agent"}) {
      if (MakeSetCommand(key.name, value, nullptr)) {
        built = true;
        break;
      }
    }
    EXPECT_TRUE(built) << key.name;
  }
}

TEST(SettingKeyTest, KeywordValueMapsToItsEnum) {
  const auto command = MakeSetCommand("axis", "both", nullptr);
  ASSERT_TRUE(command.has_value());
  EXPECT_EQ(command->set_search().axis(), kapfix::v1::AXIS_BOTH);
}

TEST(SettingKeyTest, UnknownKeyIsRefusedNamingIt) {
  std::string error;
  EXPECT_FALSE(MakeSetCommand("warp_speed", "9", &error).has_value());
  EXPECT_THAT(error, HasSubstr("unknown key 'warp_speed'"));
}

TEST(SettingKeyTest, TrailingGarbageInANumberIsRefused) {
  std::string error;
  EXPECT_FALSE(MakeSetCommand("gain", "6dB", &error).has_value());
  EXPECT_THAT(error, HasSubstr("cannot read '6dB'"));
}

TEST(SettingKeyTest, UnknownKeywordIsRefused) {
  EXPECT_FALSE(MakeSetCommand("sampling", "sometimes", nullptr).has_value());
}

TEST(SettingKeyTest, NegativeCountIsRefused) {
  EXPECT_FALSE(MakeSetCommand("patch_size", "-100", nullptr).has_value());
}

TEST(SettingKeyTest, NanParsesSoThatTheAgentRefusesIt) {
  const auto command = MakeSetCommand("p", "nan", nullptr);
  ASSERT_TRUE(command.has_value());
  EXPECT_TRUE(std::isnan(command->set_gains().p()));
}

// Issue 13: the photo keys come from PhotoSettings' schema with nothing added in kapfix-ctl.
TEST(SettingKeyTest, ShutterBestPhaseSetsThePhotoShutter) {
  std::string error;
  const auto command = MakeSetCommand("shutter", "best-phase", &error);
  ASSERT_TRUE(command.has_value()) << error;
  ASSERT_TRUE(command->has_set_photo());
  EXPECT_EQ(command->set_photo().shutter(), kapfix::v1::SHUTTER_BEST_PHASE);
  EXPECT_FALSE(command->set_photo().has_window_s());
}

TEST(SettingKeyTest, PhotoKeysSetTheirPhotoSettingsField) {
  std::string error;
  const auto window = MakeSetCommand("shutter_window", "2.5", &error);
  ASSERT_TRUE(window.has_value()) << error;
  EXPECT_FLOAT_EQ(window->set_photo().window_s(), 2.5F);
  const auto cap = MakeSetCommand("shutter_window_cap", "4", &error);
  ASSERT_TRUE(cap.has_value()) << error;
  EXPECT_FLOAT_EQ(cap->set_photo().window_cap_s(), 4.0F);
  const auto exposure = MakeSetCommand("photo_exposure", "8", &error);
  ASSERT_TRUE(exposure.has_value()) << error;
  EXPECT_FLOAT_EQ(exposure->set_photo().exposure_ms(), 8.0F);
  const auto camera = MakeSetCommand("photo_camera", "gphoto2", &error);
  ASSERT_TRUE(camera.has_value()) << error;
  EXPECT_EQ(camera->set_photo().camera(), kapfix::v1::PHOTO_CAMERA_GPHOTO2);
}

TEST(SettingKeyTest, UnknownShutterWordIsRefused) {
  std::string error;
  EXPECT_FALSE(MakeSetCommand("shutter", "best_phase", &error).has_value());
  EXPECT_THAT(error, HasSubstr("best_phase"));
}

}  // namespace
}  // namespace kapfix::link
