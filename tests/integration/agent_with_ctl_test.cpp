// Issue 3's integration tests: kapfix-agent in simulation on loopback, driven by kapfix-ctl.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>
#include <thread>

#include "kapfix/v1/command.pb.h"
#include "tests/integration/agent_process.hpp"
#include "tests/link/link_test_support.hpp"

namespace kapfix::testing {
namespace {

using ::testing::HasSubstr;

std::vector<std::filesystem::path> FilesEndingWith(const std::filesystem::path& dir,
                                                   const std::string& suffix) {
  std::vector<std::filesystem::path> files;
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(dir, ec)) {
    if (entry.path().string().ends_with(suffix)) files.push_back(entry.path());
  }
  return files;
}

TEST(AgentWithCtlTest, SspCompletesAndRecommendsASlice) {
  AgentProcess agent({"--mode", "idle"});
  const auto ssp = agent.Ctl("ssp --wait --frames 45");
  ASSERT_EQ(ssp.exit_code, 0) << ssp.err << agent.log();
  std::smatch match;
  ASSERT_TRUE(std::regex_search(ssp.out, match, std::regex("recommended_slice: (\\d+)")))
      << ssp.out;
  const int slice = std::stoi(match[1]);
  EXPECT_GE(slice, 1);
  EXPECT_LE(slice, 9);
  // The agent made it the slice in use and went back to idle, awaiting the operator.
  const auto status = agent.Ctl("status");
  EXPECT_EQ(status.exit_code, 0) << status.err;
  EXPECT_THAT(status.out, HasSubstr("mode: idle"));
  EXPECT_THAT(status.out, HasSubstr("slice: " + std::to_string(slice) + " of 9"));
}

TEST(AgentWithCtlTest, FixateConvergesUnderTheRmsTarget) {
  const std::filesystem::path report =
      std::filesystem::temp_directory_path() / ("kapfix_fixate_" + std::to_string(::getpid()));
  // At full speed, so that the flight is long enough for the predictive controller to learn
  // the swing (issue 3's figure is over a 30 s flight) whatever the machine's load.
  AgentProcess agent({"--mode", "idle", "--max-speed", "--report", report.string()});
  const auto fixate = agent.Ctl("fixate");
  ASSERT_EQ(fixate.exit_code, 0) << fixate.err << agent.log();
  // 1,800 frames of fixation (60 s flown): the start-up transient depends on the swing phase at
  // which the fixate command lands, and must not dominate the figure.
  const auto watched = agent.Ctl("watch --count 1800");
  ASSERT_EQ(watched.exit_code, 0) << watched.err;
  ASSERT_EQ(agent.Stop(), 0) << agent.log();
  std::ifstream file(report / "summary.json");
  ASSERT_TRUE(file) << "no summary.json; agent log:\n" << agent.log();
  const auto summary = nlohmann::json::parse(file);
  std::filesystem::remove_all(report);
  ASSERT_TRUE(summary["rms_error_px"].is_number()) << summary.dump();
  EXPECT_LE(summary["rms_error_px"].get<double>(), 3.0) << summary.dump();
  EXPECT_GE(summary["frames"].get<int>(), 1800) << summary.dump();
  EXPECT_EQ(summary["lock_lost_pct"].get<double>(), 0.0) << summary.dump();
}

TEST(AgentWithCtlTest, PhotoAndItsSidecarLandOnDiskAndAtTheStation) {
  AgentProcess agent;
  const std::filesystem::path station = agent.folder() / "station";
  std::filesystem::create_directories(station);
  const auto photo = agent.Ctl("photo --note integration --save " + station.string());
  ASSERT_EQ(photo.exit_code, 0) << photo.err << agent.log();
  const auto photos = FilesEndingWith(agent.photos(), ".jpg");
  ASSERT_EQ(photos.size(), 1U) << agent.log();
  std::ifstream sidecar(photos.front().string() + ".json");
  ASSERT_TRUE(sidecar) << "no sidecar for " << photos.front();
  const auto metadata = nlohmann::json::parse(sidecar);
  EXPECT_EQ(metadata["file_name"], photos.front().filename().string());
  EXPECT_EQ(metadata["width_px"], 640);
  EXPECT_EQ(metadata["lens_profile"], "default");
  EXPECT_TRUE(metadata.contains("capture_time_us"));
  EXPECT_TRUE(FilesEndingWith(agent.photos(), ".part").empty()) << "a temporary file was left";
  const auto received = FilesEndingWith(station, ".jpg");
  ASSERT_EQ(received.size(), 1U) << photo.out;
  EXPECT_EQ(std::filesystem::file_size(received.front()),
            std::filesystem::file_size(photos.front()));
}

// Issue 13 end to end: the key from the schema, the shutter in the agent, the quality in the
// sidecar kapfix-ctl writes beside the photo in a folder it makes.
TEST(AgentWithCtlTest, BestPhasePhotoSavedWithItsSidecarInANewFolder) {
  AgentProcess agent;
  const auto set = agent.Ctl("set shutter best-phase");
  ASSERT_EQ(set.exit_code, 0) << set.err << agent.log();
  const std::filesystem::path station = agent.folder() / "station" / "new";
  const auto photo = agent.Ctl("photo --note ridge --save " + station.string());
  ASSERT_EQ(photo.exit_code, 0) << photo.err << agent.log();
  const auto received = FilesEndingWith(station, ".jpg");
  ASSERT_EQ(received.size(), 1U) << photo.out;
  std::ifstream sidecar(received.front().string() + ".json");
  ASSERT_TRUE(sidecar) << "no sidecar beside " << received.front();
  const auto metadata = nlohmann::json::parse(sidecar);
  EXPECT_EQ(metadata["shutter"], "SHUTTER_BEST_PHASE") << metadata.dump();
  EXPECT_EQ(metadata["note"], "ridge");
  EXPECT_EQ(metadata["camera"], "PHOTO_CAMERA_AGENT");
  EXPECT_FALSE(metadata.value("shutter_reason", "").empty()) << metadata.dump();
  EXPECT_GT(metadata.value("sharpness_frame", 0.0), 0.0) << metadata.dump();
}

TEST(AgentWithCtlTest, MalformedCommandGetsAnErrorReplyAndTheAgentKeepsRunning) {
  AgentProcess agent;
  RawStation station("tcp://127.0.0.1:" + std::to_string(agent.command_port()));
  const auto reply = station.ExchangeBytes("\xff\xff\xff\xff not a protobuf");
  ASSERT_TRUE(reply.has_value()) << agent.log();
  EXPECT_FALSE(reply->ok());
  EXPECT_EQ(reply->error(), kapfix::v1::ERROR_CODE_MALFORMED);
  EXPECT_FALSE(reply->reason().empty());
  EXPECT_TRUE(agent.running());
  const auto status = agent.Ctl("status");
  EXPECT_EQ(status.exit_code, 0) << status.err;
  EXPECT_THAT(status.out, HasSubstr("mode: fixate"));
}

TEST(AgentWithCtlTest, OutOfRangeSettingIsRefusedWithItsReasonAndChangesNothing) {
  AgentProcess agent;
  const auto refused = agent.Ctl("set p nan");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_THAT(refused.err, HasSubstr("set_gains.p"));
  const auto accepted = agent.Ctl("set p 0.5");
  EXPECT_EQ(accepted.exit_code, 0) << accepted.err;
  const auto status = agent.Ctl("status");
  EXPECT_THAT(status.out, HasSubstr("p=0.5"));
}

}  // namespace
}  // namespace kapfix::testing
