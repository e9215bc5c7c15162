#include "agent/config/agent_config.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "agent/config_file/agent_config_file.hpp"
#include "agent/server/command_validator.hpp"

namespace kapfix::agent {
namespace {

std::string Resource(const std::string& name) {
  return std::string(KAPFIX_RESOURCES_DIR) + "/" + name;
}

// Writes configuration files into a private temporary directory, removed afterwards.
class AgentConfigFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string pattern = ::testing::TempDir() + "kapfix-config-XXXXXX";
    ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
    dir_ = pattern;
  }
  void TearDown() override {
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }
  std::string Write(const std::string& text) {
    std::string path = dir_ + "/agent.json";
    std::ofstream(path) << text;
    return path;
  }
  // Loads `text` from a file; returns the error ("" on success).
  std::string LoadError(const std::string& text) {
    AgentConfig config;
    std::string error;
    if (LoadAgentConfig(Write(text), &config, &error)) return "";
    return error;
  }
  std::string dir_;
};

TEST(AgentConfigTest, DefaultConfigIsValid) {
  std::string error;
  EXPECT_TRUE(AgentConfig{}.IsValid(&error)) << error;
}

// The defaults are the fields' `initial` option (issue 11); p is the gain the loop's figures
// are measured at.
TEST(AgentConfigTest, DefaultGainsAreTheSchemasInitialValues) {
  const kapfix::v1::Gains& gains = AgentConfig().gains;
  EXPECT_EQ(gains.controller(), kapfix::v1::CONTROLLER_KIND_PREDICTIVE);
  EXPECT_FLOAT_EQ(gains.p(), 1.0F);
  EXPECT_FLOAT_EQ(gains.i(), 0);
  EXPECT_FLOAT_EQ(gains.d(), 0);
  EXPECT_FLOAT_EQ(gains.dead_band_px(), 0.5F);
  EXPECT_FLOAT_EQ(gains.rate_limit_deg_per_s(), 90);
  EXPECT_TRUE(gains.has_i()) << "a zero default is set, not absent";
}

TEST(AgentConfigTest, AnUnsetSettingIsInvalidNamingIt) {
  AgentConfig config;
  config.gains.clear_dead_band_px();
  std::string error;
  EXPECT_FALSE(config.IsValid(&error));
  EXPECT_EQ(error, "gains.dead_band_px: not set");
  config = AgentConfig();
  config.gains.set_controller(kapfix::v1::CONTROLLER_KIND_UNSPECIFIED);
  EXPECT_FALSE(config.IsValid(&error));
  EXPECT_EQ(error, "gains.controller: not set");
}

TEST(AgentConfigTest, DefaultConfigRunsInSimulation) {
  const AgentConfig config;
  EXPECT_EQ(config.camera.backend, CameraBackend::kSim);
  EXPECT_EQ(config.servo.backend, ServoBackend::kSim);
}

TEST(AgentConfigTest, KiteExampleLoads) {
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(LoadAgentConfig(Resource("kite.json"), &config, &error)) << error;
  EXPECT_EQ(config.simulation.motion, MotionKind::kKite);
  // Both axes: under a kite line the view moves in Y too (the thesis searched X alone).
  EXPECT_EQ(config.search.axis, SearchAxis::kBoth);
}

TEST(AgentConfigTest, BoatExampleLoads) {
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(LoadAgentConfig(Resource("boat.json"), &config, &error)) << error;
  EXPECT_EQ(config.simulation.motion, MotionKind::kBoat);
  EXPECT_EQ(config.search.axis, SearchAxis::kY);
}

TEST(AgentConfigTest, ExamplesDescribeTheirHardware) {
  AgentConfig kite;
  AgentConfig boat;
  ASSERT_TRUE(LoadAgentConfig(Resource("kite.json"), &kite, nullptr));
  ASSERT_TRUE(LoadAgentConfig(Resource("boat.json"), &boat, nullptr));
  EXPECT_EQ(kite.camera.backend, CameraBackend::kAravis);
  EXPECT_EQ(kite.servo.backend, ServoBackend::kMaestro);
  EXPECT_EQ(boat.camera.backend, CameraBackend::kV4l2);
  EXPECT_EQ(boat.servo.backend, ServoBackend::kPca9685);
}

TEST(AgentConfigTest, MissingFileNamesThePathAndTheReason) {
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(LoadAgentConfig("/nonexistent/kapfix/agent.json", &config, &error));
  EXPECT_EQ(error, "/nonexistent/kapfix/agent.json: cannot read (No such file or directory)");
}

TEST_F(AgentConfigFileTest, BadJsonNamesTheFileAndTheLine) {
  const std::string error = LoadError("{\n  \"agent_id\": \"a\",\n  \"watchdog_ms\": ,\n}\n");
  EXPECT_EQ(error.rfind(dir_ + "/agent.json: invalid JSON", 0), 0u) << error;
  EXPECT_NE(error.find("line 3"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, OutOfRangeValueNamesTheField) {
  const std::string error = LoadError(R"({"camera": {"fps": 0}})");
  EXPECT_EQ(error, dir_ + "/agent.json:1: camera.fps: must be in (0, 1000], got 0.000000");
}

// Issue 11: the config loader and the command server name the range in the same words (both
// from the settings schema), and issue 15's tiny rate limit is refused by both.
TEST_F(AgentConfigFileTest, AnOutOfRangeSettingGetsTheCommandServersReason) {
  const std::string error =
      LoadError(R"({"settings": {"gains": {"rate_limit_deg_per_s": 1e-45}}})");
  EXPECT_EQ(error, dir_ +
                       "/agent.json:1: settings.gains.rate_limit_deg_per_s = 1e-45: must be in "
                       "[1, 1000] deg/s");
  kapfix::v1::Command command;
  command.mutable_set_gains()->set_rate_limit_deg_per_s(1e-45F);
  const auto reply = CommandValidator().Validate(command, kapfix::v1::AgentState());
  EXPECT_EQ(reply.reason(), "set_gains.rate_limit_deg_per_s = 1e-45: must be in [1, 1000] deg/s");
}

// The integral gain had two ranges ([0, 100] for commands, 0…10 in the config).
TEST_F(AgentConfigFileTest, TheIntegralGainHasTheCommandsRange) {
  EXPECT_EQ(LoadError(R"({"settings": {"gains": {"i": 11}}})"),
            dir_ + "/agent.json:1: settings.gains.i = 11: must be in [0, 10] 1/s");
  kapfix::v1::Command command;
  command.mutable_set_gains()->set_i(11);
  EXPECT_EQ(CommandValidator().Validate(command, kapfix::v1::AgentState()).reason(),
            "set_gains.i = 11: must be in [0, 10] 1/s");
}

TEST_F(AgentConfigFileTest, UnknownKeyIsAnError) {
  const std::string error = LoadError(R"({"servo": {"pan": {"max_degs": 30}}})");
  EXPECT_NE(error.find("servo.pan.max_degs: unknown key"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, UnknownTopLevelKeyIsAnError) {
  const std::string error = LoadError(R"({"wachdog_ms": 300})");
  EXPECT_NE(error.find("wachdog_ms: unknown key"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, UnknownEnumValueListsTheChoices) {
  const std::string error = LoadError(R"({"camera": {"backend": "usb"}})");
  EXPECT_NE(error.find("camera.backend: unknown value 'usb' (sim, v4l2 or aravis)"),
            std::string::npos)
      << error;
}

TEST_F(AgentConfigFileTest, ChannelIsGreenOrTheSumOfChannels) {
  // The settings message cannot carry the per-channel rgb of kapfix-analyze: refused by name.
  const std::string error = LoadError(R"({"settings": {"search": {"channel": "CHANNEL_RGB"}}})");
  EXPECT_NE(error.find("settings.search.channel: unknown value \"CHANNEL_RGB\" "
                       "(CHANNEL_UNSPECIFIED, CHANNEL_GREEN, CHANNEL_RGB_SUM)"),
            std::string::npos)
      << error;
  AgentConfig config;
  std::string why;
  ASSERT_TRUE(LoadAgentConfig(Write(R"({"settings": {"search": {"channel": "CHANNEL_RGB_SUM"}}})"),
                              &config, &why))
      << why;
  EXPECT_EQ(config.search.channel, ColorChannel::kRgbSum);
}

TEST_F(AgentConfigFileTest, WrongTypeIsAnError) {
  const std::string error = LoadError(R"({"settings": {"video": {"jpeg_quality": "high"}}})");
  EXPECT_NE(error.find("settings.video.jpeg_quality: must be a whole number ≥ 0, got \"high\""),
            std::string::npos)
      << error;
}

TEST_F(AgentConfigFileTest, ServoLimitOutsideItsPulseRangeIsAnError) {
  // 60 deg · 10 µs/deg from 1500 µs needs 2100 µs, beyond max_us = 2000.
  const std::string error = LoadError(R"({"servo": {"pan": {"max_deg": 60}}})");
  EXPECT_NE(error.find("servo.pan: limits"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, ReadsEachServosPlay) {
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(
      LoadAgentConfig(Write(R"({"servo": {"pan": {"play_deg": 0.3}, "tilt": {"play_deg": 0.5}}})"),
                      &config, &error))
      << error;
  EXPECT_DOUBLE_EQ(config.servo.pan.play_deg, 0.3);
  EXPECT_DOUBLE_EQ(config.servo.tilt.play_deg, 0.5);
  EXPECT_DOUBLE_EQ(AgentConfig{}.servo.pan.play_deg, 0.0);  // none assumed unless configured
}

TEST_F(AgentConfigFileTest, APlayThatIsNegativeOrBeyondABrokenServosIsAnError) {
  for (const char* play : {"-0.1", "10.5"}) {
    const std::string error =
        LoadError(std::string(R"({"servo": {"tilt": {"play_deg": )") + play + "}}}");
    EXPECT_NE(error.find("servo.tilt: play_deg"), std::string::npos) << play << ": " << error;
  }
}

TEST_F(AgentConfigFileTest, ParkOutsideTheLimitsIsAnError) {
  const std::string error = LoadError(R"({"servo": {"tilt": {"park_deg": -60}}})");
  EXPECT_NE(error.find("servo.tilt:"), std::string::npos) << error;
  EXPECT_NE(error.find("park_deg"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, LensMustNameAProfile) {
  const std::string error = LoadError(R"({"settings": {"lens": {"name": "8mm"}}})");
  // As a set_lens command: a name with no profile starts a new one, which needs its optics.
  EXPECT_EQ(error, dir_ +
                       "/agent.json: lenses[1]: lens '8mm': give either deg_per_px_pan and "
                       "deg_per_px_tilt, or focal_length_mm and pixel_pitch_um");
}

TEST_F(AgentConfigFileTest, EmptyLensListIsAnError) {
  const std::string error = LoadError(R"({"lenses": []})");
  EXPECT_NE(error.find("lenses: at least one"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, DuplicateLensNamesAreAnError) {
  const std::string error = LoadError(
      R"({"lenses": [{"name": "a", "focal_mm": 6, "pixel_pitch_um": 5},
                     {"name": "a", "focal_mm": 4, "pixel_pitch_um": 5}]})");
  EXPECT_NE(error.find("used twice"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, BadSamplingNamesTheField) {
  const std::string error = LoadError(R"({"settings": {"search": {"random_fraction": 2}}})");
  EXPECT_NE(error.find("settings.search.random_fraction = 2: must be in [0.01, 1]"),
            std::string::npos)
      << error;
}

TEST_F(AgentConfigFileTest, PatchLargerThanTheFrameIsAnError) {
  const std::string error = LoadError(R"({"camera": {"width": 320, "height": 240},
                    "settings": {"search": {"patch_size_px": 300}}})");
  EXPECT_NE(error.find("search.patch_px"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, CurveNeedsBothFiles) {
  const std::string error = LoadError(R"({"link": {"curve_secret_key_file": "/etc/k"}})");
  EXPECT_NE(error.find("link.curve_authorized_keys_file"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, SameAddressForCommandsAndStreamsIsAnError) {
  const std::string error =
      LoadError(R"({"link": {"command": "tcp://*:6000", "stream": "tcp://*:6000"}})");
  EXPECT_NE(error.find("link.stream"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, AddressWithoutPortIsAnError) {
  const std::string error = LoadError(R"({"link": {"command": "tcp://*"}})");
  EXPECT_NE(error.find("link.command"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, TinyCommandRateIsAnErrorNamingIt) {
  const std::string error = LoadError(R"({"link": {"command_rate_per_s": 1e-45}})");
  EXPECT_NE(error.find("link.command_rate_per_s"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, SharedCommandRateBelowAStationsIsAnError) {
  const std::string error =
      LoadError(R"({"link": {"command_rate_per_s": 50, "all_commands_rate_per_s": 40}})");
  EXPECT_NE(error.find("link.all_commands_rate_per_s"), std::string::npos) << error;
}

TEST_F(AgentConfigFileTest, PartialFileKeepsDefaultsForTheRest) {
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(
      LoadAgentConfig(Write(R"({"agent_id": "kite-2", "camera": {"fps": 60}})"), &config, &error))
      << error;
  EXPECT_EQ(config.agent_id, "kite-2");
  EXPECT_EQ(config.camera.fps, 60);
  EXPECT_EQ(config.camera.width, 640);
  EXPECT_EQ(config.link.command_address, "tcp://127.0.0.1:5555");
  EXPECT_EQ(config.link.stream_address, "tcp://127.0.0.1:5556");
}

TEST_F(AgentConfigFileTest, FailedLoadLeavesTheConfigUntouched) {
  AgentConfig config;
  config.agent_id = "before";
  EXPECT_FALSE(
      LoadAgentConfig(Write(R"({"agent_id": "after", "watchdog_ms": 1})"), &config, nullptr));
  EXPECT_EQ(config.agent_id, "before");
}

TEST_F(AgentConfigFileTest, I2cAddressMayBeAHexString) {
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(LoadAgentConfig(Write(R"({"servo": {"i2c_address": "0x41"}})"), &config, &error))
      << error;
  EXPECT_EQ(config.servo.i2c_address, 0x41);
}

TEST_F(AgentConfigFileTest, NullGainLeavesTheCameraGain) {
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(
      LoadAgentConfig(Write(R"({"settings": {"camera": {"gain_db": null}}})"), &config, &error))
      << error;
  EXPECT_FALSE(config.camera.settings.has_gain_db());
}

TEST_F(AgentConfigFileTest, TopLevelArrayIsAnError) {
  const std::string error = LoadError("[]");
  EXPECT_NE(error.find("must be a JSON object"), std::string::npos) << error;
}

TEST(AgentConfigTest, ServoConfigTranslatesToMaestroOptions) {
  ServoConfig servo;
  servo.backend = ServoBackend::kMaestro;
  servo.tilt.mapping.channel = 3;
  const MaestroServoDriverOptions options = servo.ToMaestroOptions();
  EXPECT_EQ(options.device, "/dev/ttyACM0");
  EXPECT_EQ(options.tilt.channel, 3);
}

TEST(AgentConfigTest, MaestroOptionsCarryTheTimeoutAndTheParkAngles) {
  ServoConfig servo;
  servo.backend = ServoBackend::kMaestro;
  servo.maestro_timeout_ms = 250;
  servo.pan.limits.park_deg = 5;
  servo.tilt.limits.park_deg = -10;
  const MaestroServoDriverOptions options = servo.ToMaestroOptions();
  EXPECT_EQ(options.serial_timeout_ms, 250);
  EXPECT_EQ(options.pan_home_deg, 5);
  EXPECT_EQ(options.tilt_home_deg, -10);
}

TEST_F(AgentConfigFileTest, MaestroTimeoutIsRead) {
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(LoadAgentConfig(Write(R"({"servo": {"maestro_timeout_ms": 200}})"), &config, &error))
      << error;
  EXPECT_EQ(config.servo.maestro_timeout_ms, 200);
}

TEST_F(AgentConfigFileTest, MaestroTimeoutOutOfRangeNamesTheKey) {
  EXPECT_NE(LoadError(R"({"servo": {"maestro_timeout_ms": 0}})")
                .find("servo.maestro_timeout_ms: must be 10…60000 ms"),
            std::string::npos);
  EXPECT_NE(LoadError(R"({"servo": {"maestro_timeout_ms": 255}})")
                .find("servo.maestro_timeout_ms: must be 10…60000 ms in 10 ms steps"),
            std::string::npos);
}

TEST_F(AgentConfigFileTest, MaestroTimeoutLongerThanTheWatchdogIsAnError) {
  const std::string error = LoadError(
      R"({"servo": {"backend": "maestro", "maestro_timeout_ms": 600}, "watchdog_ms": 500})");
  EXPECT_NE(error.find("servo.maestro_timeout_ms: 600 ms must not exceed watchdog_ms (500 ms)"),
            std::string::npos)
      << error;
}

TEST_F(AgentConfigFileTest, MaestroTimeoutNotLongerThanAFrameIsAnError) {
  const std::string error = LoadError(
      R"({"camera": {"fps": 20}, "servo": {"backend": "maestro", "maestro_timeout_ms": 50}})");
  EXPECT_NE(error.find("servo.maestro_timeout_ms: 50 ms must exceed a camera frame period"),
            std::string::npos)
      << error;
}

TEST_F(AgentConfigFileTest, MaestroTimeoutIsOnlyComparedWithTheWatchdogForTheMaestro) {
  EXPECT_EQ(LoadError(R"({"servo": {"maestro_timeout_ms": 600}, "watchdog_ms": 100})"), "");
}

TEST(AgentConfigTest, CameraDeviceOverridesTheV4l2Default) {
  CameraConfig camera;
  camera.device = "/dev/video2";
  EXPECT_EQ(camera.ToV4l2Options().device, "/dev/video2");
}

}  // namespace
}  // namespace kapfix::agent
