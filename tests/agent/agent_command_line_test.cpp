// kapfix-agent's flags turned into its configuration and options (agent/agent_command_line),
// without starting an agent: the process-level behaviour is in pipeline/agent_cli_test.cpp.
#include "agent/agent_command_line.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace kapfix::agent {
namespace {

// Parses `flags` as kapfix-agent's command line would (no program name).
struct Parsed {
  explicit Parsed(const std::string& flags) : line(app) { app.parse(flags, false); }
  CLI::App app{"kapfix-agent"};
  AgentCommandLine line;
};

TEST(AgentCommandLineTest, DurationBecomesFramesAtTheCamerasRate) {
  Parsed parsed("--sim --duration 2");
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(parsed.line.BuildConfig(&config, &error)) << error;
  const AgentOptions options = parsed.line.BuildOptions(config);
  EXPECT_EQ(options.frames, static_cast<std::uint64_t>(std::llround(2 * config.camera.fps)));
  EXPECT_TRUE(options.simulate);
}

TEST(AgentCommandLineTest, FlagsOverrideTheConfigKeysTheyName) {
  Parsed parsed(
      "--sim --controller pid --shutter best-phase --seed 17 --state-dir /tmp/s --photos /tmp/p "
      "--world realistic --max-speed --no-resume --report /tmp/r");
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(parsed.line.BuildConfig(&config, &error)) << error;
  EXPECT_EQ(config.gains.controller(), kapfix::v1::CONTROLLER_KIND_PID);
  EXPECT_EQ(config.photo.shutter(), kapfix::v1::SHUTTER_BEST_PHASE);
  EXPECT_EQ(config.simulation.seed, 17U);
  EXPECT_EQ(config.state_dir, "/tmp/s");
  EXPECT_EQ(config.photos.dir, "/tmp/p");
  EXPECT_EQ(config.simulation.world.Describe(), WorldOptions::Realistic().Describe());
  EXPECT_EQ(config.simulation.scene, kDefaultScene);
  const AgentOptions options = parsed.line.BuildOptions(config);
  EXPECT_FALSE(options.real_time);
  EXPECT_FALSE(options.resume);
  EXPECT_TRUE(options.keep_telemetry) << "--report keeps every step for the flight report";
  EXPECT_EQ(parsed.line.report_dir(), "/tmp/r");
}

// The settings' flags are made from the schema (its `flag` option) and applied as the settings
// command would be.
TEST(AgentCommandLineTest, SettingFlagsSetTheirSettings) {
  Parsed parsed("--sim --shutter-window 2 --photo-exposure 4 --photo-interval 3");
  AgentConfig config;
  std::string error;
  ASSERT_TRUE(parsed.line.BuildConfig(&config, &error)) << error;
  EXPECT_FLOAT_EQ(config.photo.window_s(), 2.0F);
  EXPECT_FLOAT_EQ(config.photo.exposure_ms(), 4.0F);
  EXPECT_FLOAT_EQ(config.photo.interval_s(), 3.0F);
  EXPECT_EQ(config.photo.shutter(), kapfix::v1::SHUTTER_INTERVAL) << "left as it was";
}

TEST(AgentCommandLineTest, AnOutOfRangeSettingFlagGetsTheSchemasReasonNamingTheFlag) {
  Parsed parsed("--sim --photo-exposure 5000");
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(parsed.line.BuildConfig(&config, &error));
  EXPECT_EQ(error, "--photo-exposure: photo.exposure_ms = 5000: must be in [0.01, 2000] ms");
}

TEST(AgentCommandLineTest, AWordThatIsNoChoiceIsRefusedNamingTheFlag) {
  Parsed parsed("--sim --controller fuzzy");
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(parsed.line.BuildConfig(&config, &error));
  EXPECT_EQ(error.rfind("--controller: cannot read 'fuzzy'", 0), 0U) << error;
  EXPECT_NE(error.find("p | pid | predictive"), std::string::npos) << error;
}

TEST(AgentCommandLineTest, SettingFlagsTakeTheirHelpFromTheSchema) {
  Parsed parsed("--sim");
  const std::string help = parsed.app.help();
  EXPECT_NE(help.find("--shutter-window"), std::string::npos) << help;
  EXPECT_NE(help.find("how long best-phase waits for the quietest moment"), std::string::npos)
      << help;
  EXPECT_NE(help.find("(overrides settings.photo.window_s)"), std::string::npos) << help;
  EXPECT_NE(help.find("--photo-interval"), std::string::npos) << help;
}

TEST(AgentCommandLineTest, AWorldFlagWithoutSimIsRefusedNamingSim) {
  Parsed parsed("--gusts broadband");
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(parsed.line.BuildConfig(&config, &error));
  EXPECT_NE(error.find("need --sim"), std::string::npos) << error;
}

TEST(AgentCommandLineTest, AnUnknownWorldPresetIsRefusedNamingIt) {
  Parsed parsed("--sim --world stormy");
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(parsed.line.BuildConfig(&config, &error));
  EXPECT_NE(error.find("stormy"), std::string::npos) << error;
}

TEST(AgentCommandLineTest, AMissingConfigFileIsRefusedNamingTheFile) {
  Parsed parsed("--config /nonexistent/kapfix.json");
  AgentConfig config;
  std::string error;
  EXPECT_FALSE(parsed.line.BuildConfig(&config, &error));
  EXPECT_NE(error.find("/nonexistent/kapfix.json"), std::string::npos) << error;
}

}  // namespace
}  // namespace kapfix::agent
