#include "agent/commands/calibration_store.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <stdexcept>

#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

using kapfix::testing::TempDir;

kapfix::v1::CalibrationReport Report() {
  kapfix::v1::CalibrationReport report;
  report.mutable_pan()->set_residual_px(0.4);
  report.mutable_tilt()->set_residual_px(0.6);
  return report;
}

TEST(CalibrationStoreTest, ASavedCalibrationIsLoadedBack) {
  TempDir dir;
  const CalibrationStore store(dir.path() / "calibration");
  store.Save("6mm", {.pan_deg_per_px = 0.021, .tilt_deg_per_px = -0.02}, Report());
  std::string error;
  const auto loaded = store.Load("6mm", &error);
  ASSERT_TRUE(loaded.has_value()) << error;
  EXPECT_DOUBLE_EQ(loaded->pan_deg_per_px, 0.021);
  EXPECT_DOUBLE_EQ(loaded->tilt_deg_per_px, -0.02);
}

TEST(CalibrationStoreTest, ALensNeverCalibratedHasNothingStoredAndNoError) {
  TempDir dir;
  const CalibrationStore store(dir.path());
  std::string error = "untouched";
  EXPECT_FALSE(store.Load("3.5mm", &error).has_value());
  EXPECT_TRUE(error.empty());
}

TEST(CalibrationStoreTest, ACorruptFileIsIgnoredNamingIt) {
  TempDir dir;
  std::ofstream(dir.path() / "default.json") << "{ not json";
  const CalibrationStore store(dir.path());
  std::string error;
  EXPECT_FALSE(store.Load("default", &error).has_value());
  EXPECT_NE(error.find("default.json"), std::string::npos) << error;
}

TEST(CalibrationStoreTest, AZeroSlopeIsNotLoaded) {
  TempDir dir;
  std::ofstream(dir.path() / "default.json") << R"({"pan_deg_per_px": 0, "tilt_deg_per_px": 0.1})";
  const CalibrationStore store(dir.path());
  std::string error;
  EXPECT_FALSE(store.Load("default", &error).has_value());
  EXPECT_FALSE(error.empty());
}

TEST(CalibrationStoreTest, ANameWithAPathSeparatorIsNeitherSavedNorLoaded) {
  TempDir dir;
  const CalibrationStore store(dir.path());
  EXPECT_THROW(store.Save("../escape", {.pan_deg_per_px = 0.1, .tilt_deg_per_px = 0.1}, Report()),
               std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(dir.path().parent_path() / "escape.json"));
  std::string error;
  EXPECT_FALSE(store.Load("../escape", &error).has_value());
}

}  // namespace
}  // namespace kapfix::agent
