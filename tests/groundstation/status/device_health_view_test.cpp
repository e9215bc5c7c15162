#include "groundstation/status/device_health_view.hpp"

#include <gtest/gtest.h>

#include "groundstation/client/fake_agent_client.hpp"
#include "tests/groundstation/station_test_support.hpp"

namespace kapfix::station {
namespace {

kapfix::v1::DeviceHealth Health(kapfix::v1::DeviceStatus status, const std::string& reason = {}) {
  kapfix::v1::DeviceHealth health;
  health.set_status(status);
  health.set_reason(reason);
  return health;
}

TEST(DeviceHealthView, SaysNothingUntilTheAgentReportsItsDevices) {
  FakeAgentClient client;
  DeviceHealthView view(client);
  client.publish(kapfix::v1::AgentState());
  EXPECT_TRUE(view.cameraText().isEmpty());
  EXPECT_TRUE(view.servoText().isEmpty());
  EXPECT_FALSE(view.anyLost());
}

TEST(DeviceHealthView, ALostServoControllerIsNamedWithItsReason) {
  FakeAgentClient client;
  DeviceHealthView view(client);
  kapfix::v1::AgentState state;
  *state.mutable_camera_health() = Health(kapfix::v1::DEVICE_OK);
  *state.mutable_servo_health() =
      Health(kapfix::v1::DEVICE_LOST, "pca9685 on /dev/i2c-1: write failed");
  client.publish(state);
  EXPECT_EQ(view.cameraText(), QStringLiteral("Camera OK"));
  EXPECT_EQ(view.servoText(), QStringLiteral("SERVOS LOST: pca9685 on /dev/i2c-1: write failed"));
  EXPECT_TRUE(view.anyLost());
}

TEST(DeviceHealthView, AWaitingCameraShowsWhatTheAgentWaitsFor) {
  FakeAgentClient client;
  DeviceHealthView view(client);
  kapfix::v1::AgentState state;
  *state.mutable_camera_health() =
      Health(kapfix::v1::DEVICE_WAITING, "cannot open /dev/video0: No such file or directory");
  client.publish(state);
  EXPECT_TRUE(view.cameraText().startsWith(QStringLiteral("Camera WAITING: cannot open")))
      << view.cameraText().toStdString();
  EXPECT_FALSE(view.anyLost());
}

// Telemetry is newer than the last state: a servo back in the next frame shows at once.
TEST(DeviceHealthView, TelemetryUpdatesTheServoHealth) {
  FakeAgentClient client;
  DeviceHealthView view(client);
  kapfix::v1::AgentState state;
  *state.mutable_servo_health() = Health(kapfix::v1::DEVICE_LOST, "write failed");
  client.publish(state);
  ASSERT_TRUE(view.anyLost());
  kapfix::v1::Telemetry telemetry = testing::MakeTelemetry(1, 0, 0, 1'000'000);
  *telemetry.mutable_servo_health() = Health(kapfix::v1::DEVICE_OK);
  client.publish(telemetry);
  EXPECT_EQ(view.servoText(), QStringLiteral("Servos OK"));
  EXPECT_FALSE(view.anyLost());
}

TEST(DeviceHealthView, ALongReasonIsShortenedInTheBarAndWholeInTheTooltip) {
  FakeAgentClient client;
  DeviceHealthView view(client);
  kapfix::v1::AgentState state;
  const std::string reason(150, 'x');
  *state.mutable_camera_health() = Health(kapfix::v1::DEVICE_LOST, reason);
  client.publish(state);
  EXPECT_LT(view.cameraText().size(), 80);
  EXPECT_EQ(view.findChildren<QLabel*>().front()->toolTip().size(), 150);
}

}  // namespace
}  // namespace kapfix::station
