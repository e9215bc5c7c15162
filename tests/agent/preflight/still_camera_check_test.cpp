// The still camera's preflight line: PASS naming the model, or FAIL with the fix for that
// kind of fault; RunPreflight adds it only when photos are taken with the still camera.
#include "agent/preflight/still_camera_check.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "agent/agent.hpp"
#include "agent/still_camera/fake_still_camera.hpp"
#include "agent/still_camera/gphoto2_still_camera.hpp"
#include "tests/support/temp_dir.hpp"

namespace kapfix::agent {
namespace {

using ::testing::HasSubstr;
using Behaviour = FakeStillCamera::Behaviour;

TEST(StillCameraCheckTest, FoundCameraPassesNamingItAndIsLeftClosed) {
  FakeStillCamera camera("jpeg");
  const PreflightCheck check = CheckStillCamera(camera);
  EXPECT_TRUE(check.pass);
  EXPECT_EQ(check.Line(),
            "PASS still camera (fake): Fake EOS on usb:001,002 found and opened (no photo taken)");
  EXPECT_FALSE(camera.open());
  EXPECT_EQ(camera.captures(), 0);
}

TEST(StillCameraCheckTest, AbsentCameraFailsWithThePtpFix) {
  FakeStillCamera camera("jpeg");
  camera.Script(Behaviour::kAbsent);
  const PreflightCheck check = CheckStillCamera(camera);
  EXPECT_FALSE(check.pass);
  EXPECT_EQ(check.detail, "no camera found");
  EXPECT_THAT(check.fix, HasSubstr("set its USB mode to PTP"));
}

TEST(StillCameraCheckTest, HeldCameraFailsNamingTheProgramsThatHoldOne) {
  FakeStillCamera camera("jpeg");
  camera.Script(Behaviour::kHeld);
  const PreflightCheck check = CheckStillCamera(camera);
  EXPECT_FALSE(check.pass);
  EXPECT_EQ(check.detail, "opening: could not claim the USB device");
  EXPECT_THAT(check.fix, HasSubstr("another program holds the camera"));
}

TEST(StillCameraCheckTest, RunPreflightChecksTheStillCameraOnlyWhenSelected) {
  kapfix::testing::TempDir temp;
  AgentConfig config = BuiltInConfig(MotionKind::kKite);
  config.simulation.scene = std::string(KAPFIX_OPENCV_DATA_DIR) + "/aero1.jpg";
  config.photos.dir = (temp.path() / "photos").string();
  const auto still_line = [](const std::vector<PreflightCheck>& checks) {
    return std::find_if(checks.begin(), checks.end(),
                        [](const PreflightCheck& c) { return c.what.starts_with("still camera"); });
  };
  const auto agent_only = RunPreflight(config, {.simulate = true});
  EXPECT_EQ(still_line(agent_only), agent_only.end());
  if (!Gphoto2StillCamera::Available()) GTEST_SKIP() << "built without libgphoto2";
  const auto checks =
      RunPreflight(config, {.simulate = true, .photo_camera = kapfix::v1::PHOTO_CAMERA_GPHOTO2});
  const auto line = still_line(checks);
  ASSERT_NE(line, checks.end());
  if (line->pass) GTEST_SKIP() << "a still camera is connected: " << line->Line();
  EXPECT_THAT(line->Line(), HasSubstr("FAIL still camera (gphoto2): no camera found"));
  EXPECT_THAT(line->Line(), HasSubstr("fix: connect the camera by USB"));
}

}  // namespace
}  // namespace kapfix::agent
