#include "agent/preflight/preflight.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "agent/agent.hpp"

namespace kapfix::agent {
namespace {

namespace fs = std::filesystem;

// A simulated configuration whose photo folder is a fresh temporary directory.
class PreflightTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("kapfix-preflight-" + std::to_string(::getpid()) + "-" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    config_ = BuiltInConfig(MotionKind::kKite);
    config_.simulation.scene = std::string(KAPFIX_OPENCV_DATA_DIR) + "/aero1.jpg";
    config_.photos.dir = (dir_ / "photos").string();
  }
  void TearDown() override { fs::remove_all(dir_); }

  const PreflightCheck* Find(const std::vector<PreflightCheck>& checks, const std::string& what) {
    for (const PreflightCheck& check : checks) {
      if (check.what.starts_with(what)) return &check;
    }
    return nullptr;
  }

  fs::path dir_;
  AgentConfig config_;
};

TEST_F(PreflightTest, SimulationOnAFreshMachinePassesEveryCheck) {
  const auto checks = RunPreflight(config_, {.simulate = true});
  ASSERT_GE(checks.size(), 4u);
  for (const PreflightCheck& check : checks) EXPECT_TRUE(check.pass) << check.Line();
}

TEST_F(PreflightTest, SecretKeyReadableByOthersFailsWithTheCommandToFixIt) {
  const fs::path key = dir_ / "agent.key";
  std::ofstream(key) << "irrelevant\n";
  ::chmod(key.c_str(), 0644);
  config_.link.curve_secret_key_file = key.string();
  config_.link.curve_authorized_keys_file = (dir_ / "authorized_keys").string();
  const auto checks = RunPreflight(config_, {.simulate = true});
  const PreflightCheck* check = Find(checks, "agent key");
  ASSERT_NE(check, nullptr);
  EXPECT_FALSE(check->pass);
  EXPECT_NE(check->Line().find("fix: chmod 600 " + key.string()), std::string::npos)
      << check->Line();
}

TEST_F(PreflightTest, MissingStationKeyFileFails) {
  config_.link.curve_secret_key_file = (dir_ / "agent.key").string();
  config_.link.curve_authorized_keys_file = (dir_ / "authorized_keys").string();
  const auto checks = RunPreflight(config_, {.simulate = true});
  const PreflightCheck* check = Find(checks, "station keys");
  ASSERT_NE(check, nullptr);
  EXPECT_FALSE(check->pass) << check->Line();
  const PreflightCheck* key = Find(checks, "agent key");
  ASSERT_NE(key, nullptr);
  EXPECT_NE(key->Line().find("FAIL agent key " + (dir_ / "agent.key").string() + ": missing"),
            std::string::npos)
      << key->Line();
}

TEST_F(PreflightTest, AbsentSerialPortFailsTheServoCheckNamingIt) {
  config_.camera.backend = CameraBackend::kV4l2;
  config_.camera.device = "/dev/video97";
  config_.servo.backend = ServoBackend::kMaestro;
  config_.servo.device = "/dev/ttyACM97";
  config_.servo.pan.limits.max_rate_deg_per_s = 120;
  const auto checks = RunPreflight(config_, {});
  const PreflightCheck* servos = Find(checks, "servos");
  ASSERT_NE(servos, nullptr);
  EXPECT_FALSE(servos->pass);
  EXPECT_NE(servos->Line().find("/dev/ttyACM97"), std::string::npos) << servos->Line();
  const PreflightCheck* camera = Find(checks, "camera");
  ASSERT_NE(camera, nullptr);
  EXPECT_FALSE(camera->pass) << camera->Line();
}

TEST_F(PreflightTest, TooLittleFreeSpaceFails) {
  PreflightOptions options{.simulate = true};
  options.min_free_bytes = ~std::uintmax_t{0};
  const auto checks = RunPreflight(config_, options);
  const PreflightCheck* check = Find(checks, "photo folder");
  ASSERT_NE(check, nullptr);
  EXPECT_FALSE(check->pass);
  EXPECT_NE(check->Line().find("MiB free (need"), std::string::npos) << check->Line();
}

}  // namespace
}  // namespace kapfix::agent
