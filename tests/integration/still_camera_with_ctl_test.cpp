// Issue 13: kapfix-agent --photo-camera gphoto2 on a machine without a still camera (this
// one, CI): kapfix-ctl's photo is still answered at once and taken, by the agent's camera,
// and its sidecar and the agent's log say why.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/integration/agent_process.hpp"

namespace kapfix::testing {
namespace {

using ::testing::HasSubstr;

TEST(StillCameraWithCtlTest, NoStillCameraConnectedGivesAnAgentCameraPhotoSayingWhy) {
  AgentProcess agent({"--photo-camera", "gphoto2"});
  const std::filesystem::path station = agent.folder() / "station";
  std::filesystem::create_directories(station);
  const auto photo = agent.Ctl("photo --note still --save " + station.string());
  ASSERT_EQ(photo.exit_code, 0) << photo.err << agent.log();
  std::vector<std::filesystem::path> sidecars;
  for (const auto& entry : std::filesystem::directory_iterator(agent.photos())) {
    if (entry.path().string().ends_with(".jpg.json")) sidecars.push_back(entry.path());
  }
  ASSERT_EQ(sidecars.size(), 1U) << agent.log();
  std::ifstream sidecar(sidecars.front());
  const auto metadata = nlohmann::json::parse(sidecar);
  if (metadata["camera"] == "PHOTO_CAMERA_GPHOTO2") GTEST_SKIP() << "a still camera is connected";
  EXPECT_EQ(metadata["camera"], "PHOTO_CAMERA_AGENT");
  EXPECT_THAT(metadata["camera_fallback_reason"].get<std::string>(),
              HasSubstr("gphoto2: no camera found"));
  EXPECT_EQ(metadata["width_px"], 640);
  EXPECT_THAT(agent.log(), HasSubstr("taken with the agent's camera instead"));
}

}  // namespace
}  // namespace kapfix::testing
