// kapfix-analyze as a script would use it: exit codes, one-line errors, JSON keys, files.
// Needs Debian's opencv-doc photos (deploy/setup-debian.sh).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

namespace {

struct Outcome {
  int exit_code = -1;
  std::string out;
  std::string err;
};

Outcome RunAnalyze(const std::string& args) {
  const std::filesystem::path err_file =
      std::filesystem::temp_directory_path() / ("kapfix_analyze_err_" + std::to_string(::getpid()));
  const std::string command = std::string(KAPFIX_ANALYZE) + " " + args + " 2>" + err_file.string();
  Outcome outcome;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (pipe == nullptr) return outcome;
  std::array<char, 4096> buffer{};
  while (std::fgets(buffer.data(), buffer.size(), pipe) != nullptr) outcome.out += buffer.data();
  const int status = ::pclose(pipe);
  outcome.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  if (FILE* err = std::fopen(err_file.c_str(), "r")) {
    while (std::fgets(buffer.data(), buffer.size(), err) != nullptr) outcome.err += buffer.data();
    std::fclose(err);
  }
  std::filesystem::remove(err_file);
  return outcome;
}

std::string Photo(const std::string& name) {
  return std::string(KAPFIX_OPENCV_DATA_DIR) + "/" + name;
}

nlohmann::json ParseJson(const Outcome& outcome) {
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  return nlohmann::json::parse(outcome.out, nullptr, /*allow_exceptions=*/false);
}

TEST(AnalyzeCliTest, SwingPrintsItsFiguresAsJson) {
  const auto json = ParseJson(
      RunAnalyze("swing --image " + Photo("aero1.jpg") + " --strategy h23 --frames 120 --json"));
  ASSERT_TRUE(json.is_object());
  for (const char* key : {"mean_abs_err_px", "within_2px_pct", "gross_fail_pct",
                          "pixels_per_estimate", "median_us_per_estimate"}) {
    EXPECT_TRUE(json.contains(key)) << key;
  }
  EXPECT_EQ(json["frames"], 120);
  // h23 over 10 % of a 100×100 patch: at most 23 + a few refinement positions × 1,000 pixels.
  EXPECT_LE(json["pixels_per_estimate"].get<double>(), 30'000.0);
}

TEST(AnalyzeCliTest, SwingWithPyrHoldsTheAerialViewDespiteTheWobble) {
  const auto json = ParseJson(
      RunAnalyze("swing --image " + Photo("aero1.jpg") + " --strategy pyr --frames 120 --json"));
  ASSERT_TRUE(json.is_object());
  EXPECT_LT(json["mean_abs_err_px"].get<double>(), 1.0);
  EXPECT_GT(json["within_2px_pct"].get<double>(), 97.0);
}

TEST(AnalyzeCliTest, SwingWithoutWobbleIsExactForTheExhaustiveSearch) {
  const auto json = ParseJson(RunAnalyze("swing --image " + Photo("aero1.jpg") +
                                         " --strategy all --jitter 0 --frames 60 --json"));
  ASSERT_TRUE(json.is_object());
  EXPECT_DOUBLE_EQ(json["gross_fail_pct"].get<double>(), 0.0);
}

TEST(AnalyzeCliTest, SwingWritesCsvAndPlotsToTheOutputFolder) {
  const auto dir = std::filesystem::temp_directory_path() / "kapfix_analyze_swing_out";
  std::filesystem::remove_all(dir);
  const Outcome outcome =
      RunAnalyze("swing --image " + Photo("aero3.jpg") + " --frames 40 --out " + dir.string());
  EXPECT_EQ(outcome.exit_code, 0) << outcome.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "swing.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "swing.png"));
  EXPECT_GT(std::filesystem::file_size(dir / "swing.csv"), 100u);
  std::filesystem::remove_all(dir);
}

TEST(AnalyzeCliTest, UnreadableImageExitsNonZeroWithOneLineNamingIt) {
  const Outcome outcome = RunAnalyze("swing --image /nonexistent/scene.jpg --json");
  EXPECT_NE(outcome.exit_code, 0);
  EXPECT_TRUE(outcome.out.empty());
  EXPECT_NE(outcome.err.find("/nonexistent/scene.jpg"), std::string::npos) << outcome.err;
  EXPECT_EQ(std::count(outcome.err.begin(), outcome.err.end(), '\n'), 1) << outcome.err;
}

TEST(AnalyzeCliTest, UnknownStrategyExitsNonZeroNamingIt) {
  const Outcome outcome =
      RunAnalyze("swing --image " + Photo("aero1.jpg") + " --strategy h99 --frames 10");
  EXPECT_NE(outcome.exit_code, 0);
  EXPECT_NE(outcome.err.find("h99"), std::string::npos) << outcome.err;
}

TEST(AnalyzeCliTest, BadArgumentsExitNonZeroWithOneLine) {
  const Outcome outcome = RunAnalyze("swing --frames -3");
  EXPECT_EQ(outcome.exit_code, 2);
  EXPECT_EQ(std::count(outcome.err.begin(), outcome.err.end(), '\n'), 1) << outcome.err;
}

TEST(AnalyzeCliTest, SurfaceReportsSuccessRateAndSampledPixels) {
  const auto json = ParseJson(
      RunAnalyze("surface --image " + Photo("fruits.jpg") + " --sampling random:0.25 --json"));
  ASSERT_TRUE(json.is_object());
  EXPECT_EQ(json["sampled_pixels"], 2500);  // the thesis's random count (Table 3.2)
  const double success = json["success_pct"].get<double>();
  EXPECT_GT(success, 0.0);
  EXPECT_LE(success, 100.0);
}

TEST(AnalyzeCliTest, SspRecommendsOneOfTheSlices) {
  const auto json =
      ParseJson(RunAnalyze("ssp --image " + Photo("aero1.jpg") + " --frames 80 --json"));
  ASSERT_TRUE(json.is_object());
  ASSERT_EQ(json["slices"].size(), 9u);
  const int best = json["best_slice"].get<int>();
  EXPECT_GE(best, 1);
  EXPECT_LE(best, 9);
  for (const auto& slice : json["slices"]) {
    EXPECT_TRUE(slice.contains("dc") && slice.contains("fft") && slice.contains("single_shot"));
  }
}

TEST(AnalyzeCliTest, SspValidateReportsSpearmanPerScore) {
  const auto json = ParseJson(RunAnalyze("ssp --image " + Photo("building.jpg") +
                                         " --frames 60 --slices 5 --validate --json"));
  ASSERT_TRUE(json.is_object());
  ASSERT_TRUE(json.contains("spearman"));
  for (const char* score : {"dc", "dc-hyst", "fft", "single-shot"}) {
    EXPECT_TRUE(json["spearman"].contains(score)) << score;
  }
  EXPECT_TRUE(json["slices"][0].contains("gross_fail_pct"));
}

TEST(AnalyzeCliTest, PssPicksOneOfTheCandidateSizes) {
  const auto json = ParseJson(
      RunAnalyze("pss --image " + Photo("aero3.jpg") + " --sizes 50,100 --frames 60 --json"));
  ASSERT_TRUE(json.is_object());
  ASSERT_EQ(json["sizes"].size(), 2u);
  const int best = json["best_size"].get<int>();
  EXPECT_TRUE(best == 50 || best == 100);
}

TEST(AnalyzeCliTest, CompareReportsAKruskalWallisPValue) {
  const auto json = ParseJson(RunAnalyze("compare --image " + Photo("left01.jpg") +
                                         " --strategies all,h23,h15 --frames 80 --json"));
  ASSERT_TRUE(json.is_object());
  const double p = json["p_value"].get<double>();
  EXPECT_GE(p, 0.0);
  EXPECT_LE(p, 1.0);
  EXPECT_EQ(json["strategies"].size(), 3u);
}

}  // namespace
