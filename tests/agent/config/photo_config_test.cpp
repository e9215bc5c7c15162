// The photos section's shutter settings (issue 13): read from the config file with the same
// strictness as the other keys, checked against the settings schema, and a window longer than
// its cap refused.
#include "agent/config/photo_config.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "agent/config/agent_config.hpp"
#include "agent/config_file/agent_config_file.hpp"
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
  const PhotoConfig photos;
  EXPECT_EQ(photos.shutter, ShutterMode::kInterval);
  EXPECT_EQ(photos.window_s, 0.0);
  EXPECT_EQ(photos.window_cap_s, 10.0);
  EXPECT_EQ(photos.exposure_ms, 10.0);
  EXPECT_EQ(photos.camera, PhotoCameraKind::kAgent);
  std::string error;
  EXPECT_TRUE(photos.IsValid(&error)) << error;
}

TEST(PhotoConfigTest, ConfigFileReadsTheShutterKeys) {
  TempDir dir;
  AgentConfig config;
  ASSERT_EQ(Load(dir,
                 R"({"settings": {"photo": {"shutter": "SHUTTER_BEST_PHASE", "window_s": 2.5,
                     "window_cap_s": 4, "exposure_ms": 20, "camera": "PHOTO_CAMERA_GPHOTO2"}}})",
                 &config),
            "");
  EXPECT_EQ(config.photos.shutter, ShutterMode::kBestPhase);
  EXPECT_DOUBLE_EQ(config.photos.window_s, 2.5);
  EXPECT_DOUBLE_EQ(config.photos.window_cap_s, 4.0);
  EXPECT_DOUBLE_EQ(config.photos.exposure_ms, 20.0);
  EXPECT_EQ(config.photos.camera, PhotoCameraKind::kGphoto2);
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
  PhotoConfig photos;
  photos.window_s = 12;
  photos.window_cap_s = 10;
  std::string error;
  EXPECT_FALSE(photos.IsValid(&error));
  EXPECT_NE(error.find("photos.window_s = 12"), std::string::npos) << error;
  EXPECT_NE(error.find("longer than photos.window_cap_s = 10"), std::string::npos) << error;
}

TEST(PhotoConfigTest, ExposureThatIsNotPositiveIsRefused) {
  PhotoConfig photos;
  photos.exposure_ms = 0;
  std::string error;
  EXPECT_FALSE(photos.IsValid(&error));
  EXPECT_NE(error.find("photos.exposure_ms = 0"), std::string::npos) << error;
  photos.exposure_ms = -5;
  EXPECT_FALSE(photos.IsValid(&error));
}

TEST(PhotoConfigTest, WindowBeyondTheSchemaIsRefusedFromTheFile) {
  TempDir dir;
  AgentConfig config;
  const std::string error =
      Load(dir, R"({"settings": {"photo": {"window_s": 40, "window_cap_s": 30}}})", &config);
  EXPECT_NE(error.find("window_s = 40"), std::string::npos) << error;
}

TEST(PhotoConfigTest, ShutterWordsReadBack) {
  for (const ShutterMode mode : {ShutterMode::kInterval, ShutterMode::kBestPhase}) {
    EXPECT_EQ(ParseShutterMode(ToString(mode)), mode);
  }
  EXPECT_FALSE(ParseShutterMode("best_phase"));
}

}  // namespace
}  // namespace kapfix::agent
