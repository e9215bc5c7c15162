// The shutter settings (issue 13), held as kapfix.v1.PhotoSettings in AgentConfig::photo
// (issue 11): read from the config file with the same strictness as the other keys, checked
// against the settings schema, and a window longer than its cap refused.
#include "agent/config/photo_config.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "agent/config/agent_config.hpp"
#include "agent/config_file/agent_config_file.hpp"
#include "common/shutter/best_phase_shutter.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

using kapfix::testing::TempDir;

// Loads `text` as a config file; the error ("" on success) and the config.
std::string Load(const TempDir& dir, const std::string& text, AgentConfig* config) {
  const auto path = dir.path() / "agent.json";
  std::ofstream(path) << text;
  std::string error;
  if (LoadAgentConfig(path.string(), config, &error)) return "";
  return error;
}

TEST(PhotoConfigTest, DefaultsAreIntervalOnePeriodTenSecondCapTenMillisecondsAgentCamera) {
  const AgentConfig config;
  EXPECT_EQ(config.photo.shutter(), kapfix::v1::SHUTTER_INTERVAL);
  EXPECT_EQ(config.photo.window_s(), 0.0F);
  EXPECT_EQ(config.photo.window_cap_s(), 10.0F);
  EXPECT_EQ(config.photo.exposure_ms(), 10.0F);
  EXPECT_EQ(config.photo.camera(), kapfix::v1::PHOTO_CAMERA_AGENT);
  std::string error;
  EXPECT_TRUE(config.IsValid(&error)) << error;
}

TEST(PhotoConfigTest, ConfigFileReadsTheShutterKeys) {
  TempDir dir;
  AgentConfig config;
  ASSERT_EQ(Load(dir,
                 R"({"settings": {"photo": {"shutter": "SHUTTER_BEST_PHASE", "window_s": 2.5,
                     "window_cap_s": 4, "exposure_ms": 20, "camera": "PHOTO_CAMERA_GPHOTO2"}}})",
                 &config),
            "");
  EXPECT_EQ(config.photo.shutter(), kapfix::v1::SHUTTER_BEST_PHASE);
  EXPECT_FLOAT_EQ(config.photo.window_s(), 2.5F);
  EXPECT_FLOAT_EQ(config.photo.window_cap_s(), 4.0F);
  EXPECT_FLOAT_EQ(config.photo.exposure_ms(), 20.0F);
  EXPECT_EQ(config.photo.camera(), kapfix::v1::PHOTO_CAMERA_GPHOTO2);
}

TEST(PhotoConfigTest, UnknownShutterWordListsTheChoices) {
  TempDir dir;
  AgentConfig config;
  const std::string error = Load(dir, R"({"settings": {"photo": {"shutter": "best"}}})", &config);
  EXPECT_NE(error.find(":1: settings.photo.shutter: unknown value \"best\" (SHUTTER_UNSPECIFIED, "
                       "SHUTTER_INTERVAL, SHUTTER_BEST_PHASE)"),
            std::string::npos)
      << error;
}

TEST(PhotoConfigTest, WrongTypeOfExposureIsAnError) {
  TempDir dir;
  AgentConfig config;
  const std::string error = Load(dir, R"({"settings": {"photo": {"exposure_ms": "10"}}})", &config);
  EXPECT_NE(error.find(":1: settings.photo.exposure_ms: must be a number"), std::string::npos)
      << error;
}

TEST(PhotoConfigTest, WindowLongerThanTheCapIsRefused) {
  AgentConfig config;
  config.photo.set_window_s(12);
  config.photo.set_window_cap_s(10);
  std::string error;
  EXPECT_FALSE(config.IsValid(&error));
  EXPECT_EQ(error,
            "photo: shutter window 12.00 s is longer than its cap 10.00 s: shorten the window or "
            "raise the cap");
}

TEST(PhotoConfigTest, ExposureThatIsNotPositiveIsRefused) {
  AgentConfig config;
  config.photo.set_exposure_ms(0);
  std::string error;
  EXPECT_FALSE(config.IsValid(&error));
  EXPECT_EQ(error, "photo.exposure_ms = 0: must be in [0.01, 2000] ms");
  config.photo.set_exposure_ms(-5);
  EXPECT_FALSE(config.IsValid(&error));
}

TEST(PhotoConfigTest, WindowBeyondTheSchemaIsRefusedFromTheFile) {
  TempDir dir;
  AgentConfig config;
  const std::string error =
      Load(dir, R"({"settings": {"photo": {"window_s": 40, "window_cap_s": 30}}})", &config);
  EXPECT_NE(error.find("window_s = 40"), std::string::npos) << error;
}

TEST(PhotoConfigTest, ShutterWordsAreTheSchemas) {
  EXPECT_EQ(ParseShutterMode(kapfix::v1::WordOf(kapfix::v1::SHUTTER_INTERVAL)),
            ShutterMode::kInterval);
  EXPECT_EQ(ParseShutterMode(kapfix::v1::WordOf(kapfix::v1::SHUTTER_BEST_PHASE)),
            ShutterMode::kBestPhase);
  EXPECT_FALSE(ParseShutterMode("best_phase"));
}

}  // namespace
}  // namespace kapfix::agent
