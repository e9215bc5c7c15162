// kapfix-bench-loop as a user runs it: the same output whatever --jobs, the plan without
// flying, a one-line refusal. Needs Debian's opencv-doc photos (deploy/setup-debian.sh).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "tests/support/process.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using kapfix::testing::ProcessOutcome;
using kapfix::testing::ReadFile;
using kapfix::testing::RunProcess;

// Runs the benchmark in `dir` (its --out is relative, so stdout names the same folder
// whatever `dir`), stderr to dir/stderr.txt.
ProcessOutcome RunLoopBench(const std::filesystem::path& dir, const std::string& args) {
  return RunProcess("cd '" + dir.string() + "' && " + KAPFIX_BENCH_LOOP + " " + args,
                    dir / "stderr.txt");
}

// 2 scenes × 2 worlds × both starts × predictive and P, 1 seed, 30 frames, with traces; SSP's
// free swing shortened to 40 frames by an agent configuration in the run's folder (it flew
// most of the test's frames, and the test was the slowest of the suite).
constexpr const char* kTinyMatrix =
    "--quick --frames 30 --seeds 1 --sweep-scenes 1 --scenes aero1.jpg left01.jpg --worlds "
    "nominal realistic --start both --controllers predictive --trace --out out --config "
    "short_swing.json";

void WriteShortSwingConfig(const std::filesystem::path& dir) {
  std::ofstream(dir / "short_swing.json") << R"({"search": {"swing_frames": 40}})";
}

TEST(LoopBenchmarkTest, OutputIsTheSameByteForByteWhateverTheJobs) {
  const kapfix::testing::TempDir one, three;
  WriteShortSwingConfig(one.path());
  WriteShortSwingConfig(three.path());
  const ProcessOutcome serial = RunLoopBench(one.path(), std::string(kTinyMatrix) + " --jobs 1");
  const ProcessOutcome parallel =
      RunLoopBench(three.path(), std::string(kTinyMatrix) + " --jobs 3");
  ASSERT_EQ(serial.exit_code, 0) << ReadFile(one.path() / "stderr.txt");
  ASSERT_EQ(parallel.exit_code, 0) << ReadFile(three.path() / "stderr.txt");
  EXPECT_EQ(serial.out, parallel.out);
  std::size_t files = 0, traces = 0;
  for (const auto& entry : std::filesystem::directory_iterator(one.path() / "out")) {
    const std::filesystem::path name = entry.path().filename();
    const std::string bytes = ReadFile(entry.path());
    EXPECT_FALSE(bytes.empty()) << name;
    EXPECT_TRUE(bytes == ReadFile(three.path() / "out" / name)) << name << " differs";
    ++files;
    traces += name.string().rfind("trace_", 0) == 0 ? 1 : 0;
  }
  // The sweep: 2 worlds × 3 gains × 1 scene; the main flights: 2 × 2 starts × 2 scenes × 2;
  // P's main flight from the first frame on the sweep's scene is a sweep flight (the same
  // trace) in each world.
  EXPECT_EQ(traces, 6U + 16U - 2U);
  EXPECT_EQ(files, traces + 3U) << "loop.csv, loop_heatmap.png, summary.json";
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(three.path() / "out"),
                          std::filesystem::directory_iterator()),
            static_cast<std::ptrdiff_t>(files));
  // Progress names every flight as it finishes.
  EXPECT_NE(ReadFile(three.path() / "stderr.txt").find("[22/22]"), std::string::npos);
}

TEST(LoopBenchmarkTest, DryRunPrintsThePlanAndFliesNothing) {
  const kapfix::testing::TempDir dir;
  const ProcessOutcome outcome = RunLoopBench(dir.path(), "--dry-run --seeds 3 --jobs 2 --out out");
  ASSERT_EQ(outcome.exit_code, 0) << ReadFile(dir.path() / "stderr.txt");
  EXPECT_NE(outcome.out.find("12 worlds × 9 gains × 10 scenes (seed 1, first-frame) = 1080"),
            std::string::npos)
      << outcome.out;
  EXPECT_NE(outcome.out.find("12 worlds × 1 starts × 10 scenes × 3 seeds × 3 controllers = 1080"),
            std::string::npos)
      << outcome.out;
  EXPECT_NE(outcome.out.find("2160 flights of 500 frames, about"), std::string::npos)
      << outcome.out;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out"));
}

TEST(LoopBenchmarkTest, ByDefaultItFliesTheAgentsBuiltInLoopWithItsRateLimit) {
  const kapfix::testing::TempDir dir;
  const ProcessOutcome outcome = RunLoopBench(dir.path(), "--dry-run --out out");
  ASSERT_EQ(outcome.exit_code, 0) << ReadFile(dir.path() / "stderr.txt");
  // settings.proto's initial rate limit, the agent's 30 frames/s and 120 deg/s servos.
  EXPECT_NE(outcome.out.find(
                "predictive controller (p 1, i 0, d 0, dead_band_px 0.5, rate_limit_deg_per_s 90)"),
            std::string::npos)
      << outcome.out;
  EXPECT_NE(outcome.out.find("30 frames/s; servos 4.0 deg/frame"), std::string::npos)
      << outcome.out;
}

TEST(LoopBenchmarkTest, ConfigFliesThatConfigurationsLoop) {
  const kapfix::testing::TempDir dir;
  const ProcessOutcome outcome = RunLoopBench(
      dir.path(), "--dry-run --out out --config " KAPFIX_SOURCE_DIR "/resources/kite.json");
  ASSERT_EQ(outcome.exit_code, 0) << ReadFile(dir.path() / "stderr.txt");
  EXPECT_NE(outcome.out.find("p 1, i 0, d 0, dead_band_px 0.5, rate_limit_deg_per_s 120"),
            std::string::npos)
      << outcome.out;
  EXPECT_NE(outcome.out.find("60 frames/s; servos 2.5 deg/frame"), std::string::npos)
      << outcome.out;
  EXPECT_NE(outcome.out.find("note: the simulated swing is defined in frames and pixels"),
            std::string::npos)
      << outcome.out;
}

TEST(LoopBenchmarkTest, ABadConfigIsRefusedNamingTheField) {
  const kapfix::testing::TempDir dir;
  { std::ofstream(dir.path() / "bad.json") << R"({"camera": {"fps": -5}})"; }
  const ProcessOutcome outcome = RunLoopBench(dir.path(), "--dry-run --out out --config bad.json");
  EXPECT_EQ(outcome.exit_code, 2);
  const std::string err = ReadFile(dir.path() / "stderr.txt");
  EXPECT_NE(err.find("camera.fps"), std::string::npos) << err;
}

TEST(LoopBenchmarkTest, UnknownWorldIsRefusedInOneLineNamingTheKnownOnes) {
  const kapfix::testing::TempDir dir;
  const ProcessOutcome outcome = RunLoopBench(dir.path(), "--worlds nominal windy --out out");
  EXPECT_EQ(outcome.exit_code, 2);
  const std::string err = ReadFile(dir.path() / "stderr.txt");
  EXPECT_NE(err.find("unknown world in --worlds (known: nominal broadband"), std::string::npos)
      << err;
  EXPECT_EQ(err.find('\n'), err.size() - 1) << err;
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "out"));
}

}  // namespace
