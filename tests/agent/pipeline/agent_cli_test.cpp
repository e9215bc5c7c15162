// kapfix-agent run as a process, as a script would.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace {

struct Outcome {
  int exit_code = -1;
  std::string err;
};

std::filesystem::path ScratchDir() {
  std::string pattern =
      (std::filesystem::temp_directory_path() / "kapfix_agent_cli_XXXXXX").string();
  const char* made = ::mkdtemp(pattern.data());
  EXPECT_NE(made, nullptr);
  return made ? std::filesystem::path(made) : std::filesystem::path();
}

Outcome RunAgent(const std::string& args, const std::filesystem::path& scratch) {
  const std::filesystem::path err_file = scratch / "stderr.txt";
  // Private link addresses, photo and state folders, at full speed: tests run side by side.
  // No resume: each run from its flags.
  const std::string link =
      " --max-speed --no-resume --command-address ipc://" + (scratch / "commands").string() +
      " --stream-address ipc://" + (scratch / "streams").string() + " --photos " +
      (scratch / "photos").string() + " --state-dir " + (scratch / "state").string();
  const std::string command = std::string(KAPFIX_AGENT) + " " + args + link + " >" +
                              (scratch / "stdout.txt").string() + " 2>" + err_file.string();
  Outcome outcome;
  const int status = std::system(command.c_str());
  outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream err(err_file);
  outcome.err.assign(std::istreambuf_iterator<char>(err), std::istreambuf_iterator<char>());
  return outcome;
}

TEST(AgentCliTest, SimFlightWritesTheReport) {
  const auto scratch = ScratchDir();
  const auto report = scratch / "report";
  const Outcome o = RunAgent("--sim --frames 100 --report " + report.string(), scratch);
  ASSERT_EQ(o.exit_code, 0) << o.err;
  EXPECT_NE(o.err.find("simulation"), std::string::npos) << "it must say it runs in simulation";
  std::ifstream file(report / "summary.json");
  ASSERT_TRUE(file) << "no summary.json";
  const auto json = nlohmann::json::parse(file, nullptr, /*allow_exceptions=*/false);
  ASSERT_TRUE(json.is_object());
  for (const char* key :
       {"rms_error_px", "lock_lost_pct", "frames", "fps", "loop_latency_p50_ms",
        "loop_latency_p99_ms", "rss_mb", "controller", "scene", "motion", "p95_error_px",
        "gross_pct", "silent_gross_pct", "deg_per_px_estimate_ratio", "world"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json["frames"], 100);
  EXPECT_EQ(json["controller"], "predictive");
  EXPECT_EQ(json["motion"], "kite");
  EXPECT_TRUE(json["rms_error_px"].is_number());
  // The predictive controller's online calibration against the simulated truth (issue 9).
  EXPECT_TRUE(json["deg_per_px_estimate_ratio"].is_number()) << json.dump();
  EXPECT_FALSE(json.contains("deg_per_px_estimate_missing")) << json.dump();
  EXPECT_GT(json["rss_mb"].get<double>(), 0.0);
  EXPECT_GT(json["fps"].get<double>(), 0.0);
  EXPECT_TRUE(std::filesystem::is_regular_file(report / "telemetry.csv"));
  EXPECT_GT(std::filesystem::file_size(report / "displacement.png"), 1000u);
  // Atomic writes leave no temporary files behind.
  for (const auto& entry : std::filesystem::directory_iterator(report)) {
    EXPECT_NE(entry.path().extension(), ".part") << entry.path();
  }
  std::ifstream csv(report / "telemetry.csv");
  std::string line;
  int rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 101);  // header + one row per frame
  std::filesystem::remove_all(scratch);
}

TEST(AgentCliTest, ABadConfigPathExitsNonZeroNamingTheFile) {
  const auto scratch = ScratchDir();
  const std::string missing = (scratch / "no_such_agent.json").string();
  const Outcome o = RunAgent("--config " + missing + " --frames 5", scratch);
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.err.find(missing), std::string::npos) << o.err;
  std::filesystem::remove_all(scratch);
}

TEST(AgentCliTest, WorldFlagsWithoutSimAreRefused) {
  const auto scratch = ScratchDir();
  const Outcome o = RunAgent("--world realistic --frames 5", scratch);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.err.find("need --sim"), std::string::npos) << o.err;
  std::filesystem::remove_all(scratch);
}

TEST(AgentCliTest, AWorldFlagOutOfRangeIsRefusedInOneLineNamingIt) {
  const auto scratch = ScratchDir();
  const Outcome o = RunAgent("--sim --frame-drops 0.9 --frames 5", scratch);
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.err.find("--frame-drops"), std::string::npos) << o.err;
  EXPECT_EQ(std::count(o.err.begin(), o.err.end(), '\n'), 1) << o.err;
  std::filesystem::remove_all(scratch);
}

TEST(AgentCliTest, AMissingSceneExitsNonZeroNamingIt) {
  const auto scratch = ScratchDir();
  const Outcome o = RunAgent("--sim --frames 5 --scene /nonexistent/scene.png", scratch);
  EXPECT_NE(o.exit_code, 0);
  EXPECT_NE(o.err.find("/nonexistent/scene.png"), std::string::npos) << o.err;
  std::filesystem::remove_all(scratch);
}

}  // namespace
