// The configuration file's errors name the file, the line and the field (issue 11), for each
// kind of error; its "settings" object is the kapfix.v1 settings messages in protobuf's JSON.
#include "agent/config_file/agent_config_file.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace kapfix::agent {
namespace {

class AgentConfigFileLineTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = ::testing::TempDir() + "kapfix-config-file-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override {
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }
  // Loads a file whose line 4 is `line4` inside settings.gains; returns the error.
  std::string GainsError(const std::string& line4) {
    const std::string path = dir_ + "/agent.json";
    std::ofstream(path) << "{\n  \"settings\": {\n    \"gains\": {\n      " << line4
                        << "\n    }\n  }\n}\n";
    AgentConfig config;
    std::string error;
    EXPECT_FALSE(LoadAgentConfig(path, &config, &error));
    return error;
  }
  std::string Prefix() const { return dir_ + "/agent.json:4: "; }
  std::string dir_;
};

TEST_F(AgentConfigFileLineTest, AnOutOfRangeSettingNamesTheLineAndTheKey) {
  EXPECT_EQ(GainsError("\"p\": 11"), Prefix() + "settings.gains.p = 11: must be in [0.01, 10]");
}

TEST_F(AgentConfigFileLineTest, AnUnknownFieldNamesTheLineAndTheKey) {
  EXPECT_EQ(GainsError("\"kp\": 1"),
            Prefix() +
                "settings.gains.kp: unknown field of kapfix.v1.Gains (a typo? see "
                "resources/README.md)");
}

TEST_F(AgentConfigFileLineTest, AWrongTypeNamesTheLineAndTheKey) {
  EXPECT_EQ(GainsError("\"p\": \"high\""),
            Prefix() + "settings.gains.p: must be a number, got \"high\"");
}

TEST_F(AgentConfigFileLineTest, AnUnknownEnumNameNamesTheLineAndListsTheNames) {
  EXPECT_EQ(GainsError("\"controller\": \"pid\""),
            Prefix() +
                "settings.gains.controller: unknown value \"pid\" (CONTROLLER_KIND_UNSPECIFIED, "
                "CONTROLLER_KIND_P, CONTROLLER_KIND_PID, CONTROLLER_KIND_PREDICTIVE)");
}

TEST_F(AgentConfigFileLineTest, AnUnknownSettingsKeyListsTheKeys) {
  const std::string path = dir_ + "/agent.json";
  std::ofstream(path) << "{\n  \"settings\": {\n    \"gain\": {}\n  }\n}\n";
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(LoadAgentConfig(path, &config, &error));
  EXPECT_EQ(error.rfind(dir_ + "/agent.json:3: settings.gain: unknown key (gains, search, ", 0), 0u)
      << error;
}

TEST_F(AgentConfigFileLineTest, AnUnknownDeviceKeyNamesTheLineAndTheKey) {
  const std::string path = dir_ + "/agent.json";
  std::ofstream(path)
      << "{\n  \"servo\": {\n    \"pan\": {\n      \"max_degs\": 30\n    }\n  }\n}\n";
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(LoadAgentConfig(path, &config, &error));
  EXPECT_EQ(error.rfind(Prefix() + "servo.pan.max_degs: unknown key", 0), 0u) << error;
}

// A file written before the operator settings moved into "settings" is refused with what
// changed, not just "unknown key".
TEST_F(AgentConfigFileLineTest, AnOldFormatFileSaysWhereTheSettingsWent) {
  const std::string path = dir_ + "/agent.json";
  std::ofstream(path) << "{\n  \"agent_id\": \"a\",\n  \"controller\": {\"kp\": 0.8}\n}\n";
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(LoadAgentConfig(path, &config, &error));
  EXPECT_EQ(error.rfind(dir_ + "/agent.json:3: controller: unknown key", 0), 0u) << error;
  EXPECT_NE(error.find("the operator settings moved to \"settings\""), std::string::npos) << error;
}

TEST(AgentConfigSettingsTest, SettingsAreAppliedAsTheirCommands) {
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(ParseAgentConfig(R"({"settings": {
      "gains": {"controller": "CONTROLLER_KIND_PID", "p": 0.5, "deadBandPx": 2},
      "search": {"axis": "AXIS_BOTH", "patch_size_px": 64},
      "camera": {"auto_exposure": true},
      "video": {"jpeg_quality": 50},
      "photo": {"interval_s": 2}}})",
                               &config, &error))
      << error;
  EXPECT_EQ(config.gains.controller(), kapfix::v1::CONTROLLER_KIND_PID);
  EXPECT_DOUBLE_EQ(config.gains.p(), 0.5);
  EXPECT_DOUBLE_EQ(config.gains.dead_band_px(), 2);  // protobuf's lowerCamel name
  EXPECT_EQ(config.search.axis, SearchAxis::kBoth);
  EXPECT_EQ(config.search.patch_px, 64);
  EXPECT_FALSE(config.camera.settings.has_exposure_us());
  EXPECT_EQ(config.video.jpeg_quality(), 50U);
  EXPECT_FLOAT_EQ(config.photo.interval_s(), 2.0F);
}

TEST(AgentConfigSettingsTest, ThePhotoIntervalHasTheCommandsRange) {
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(
      ParseAgentConfig(R"({"settings": {"photo": {"interval_s": 0.1}}})", &config, &error));
  EXPECT_EQ(error, "line 1: settings.photo.interval_s = 0.1: must be in 0 (off) or [0.5, 86400] s");
}

TEST(AgentConfigSettingsTest, TheOlderPhotoIntervalKeyIsRefusedSayingWhereItWent) {
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(ParseAgentConfig(R"({"settings": {"photo_interval_s": 5}})", &config, &error));
  EXPECT_NE(error.find("settings.photo_interval_s: unknown key"), std::string::npos) << error;
  EXPECT_NE(error.find("the photo interval moved into photo"), std::string::npos) << error;
}

// The lens profiles are kapfix.v1.LensProfile in protobuf's JSON mapping (plus deg/px): the
// settings' names and ranges, unknown keys refused with the line.
TEST(AgentConfigSettingsTest, ALensProfileTakesTheSettingsFieldNames) {
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(ParseAgentConfig(
      R"({"lenses": [{"name": "a", "focal_length_mm": 6, "pixel_pitch_um": 5}]})", &config, &error))
      << error;
  ASSERT_EQ(config.lenses.size(), 1U);
  EXPECT_DOUBLE_EQ(config.lenses[0].focal_mm, 6);
  EXPECT_DOUBLE_EQ(config.lenses[0].pixel_pitch_um, 5);
}

TEST(AgentConfigSettingsTest, TheOlderFocalKeyOfALensProfileIsStillRead) {
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(ParseAgentConfig(
      R"({"lenses": [{"name": "a", "focal_mm": 3.5, "pixel_pitch_um": 5}]})", &config, &error))
      << error;
  ASSERT_EQ(config.lenses.size(), 1U);
  EXPECT_DOUBLE_EQ(config.lenses[0].focal_mm, 3.5);
}

TEST(AgentConfigSettingsTest, ALensProfileDirectDegPerPxIsRead) {
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(ParseAgentConfig(
      R"({"lenses": [{"name": "w", "deg_per_px_pan": 0.09, "deg_per_px_tilt": -0.08}]})", &config,
      &error))
      << error;
  ASSERT_EQ(config.lenses.size(), 1U);
  EXPECT_DOUBLE_EQ(config.lenses[0].deg_per_px_pan, 0.09);
  EXPECT_DOUBLE_EQ(config.lenses[0].deg_per_px_tilt, -0.08);
  EXPECT_EQ(config.lens, "w");
}

TEST(AgentConfigSettingsTest, ALensPitchOutOfRangeGetsTheSchemasReasonWithItsLine) {
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(ParseAgentConfig(
      "{\n\"lenses\": [{\"name\": \"a\", \"focal_length_mm\": 6, \"pixel_pitch_um\": 300}]}",
      &config, &error));
  EXPECT_EQ(error, "line 2: lenses[0].pixel_pitch_um = 300: must be in [0.5, 200] µm");
}

TEST(AgentConfigSettingsTest, AnUnknownLensKeyIsRefusedNamingIt) {
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(ParseAgentConfig(
      R"({"lenses": [{"name": "a", "focal_length_mm": 6, "pixel_pich_um": 5}]})", &config, &error));
  EXPECT_NE(error.find("lenses[0].pixel_pich_um: unknown field of kapfix.v1.LensProfile"),
            std::string::npos)
      << error;
}

TEST(AgentConfigSettingsTest, TheFirstLensProfileIsFittedUnlessSettingsNameAnother) {
  AgentConfig config;
  std::string error;
  const std::string lenses =
      R"("lenses": [{"name": "a", "focal_mm": 6, "pixel_pitch_um": 5},
                    {"name": "b", "focal_mm": 4, "pixel_pitch_um": 5}])";
  ASSERT_TRUE(ParseAgentConfig("{" + lenses + "}", &config, &error)) << error;
  EXPECT_EQ(config.lens, "a");
  ASSERT_TRUE(
      ParseAgentConfig("{" + lenses + R"(, "settings": {"lens": {"name": "b"}}})", &config, &error))
      << error;
  EXPECT_EQ(config.lens, "b");
}

}  // namespace
}  // namespace kapfix::agent
