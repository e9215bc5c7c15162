// kapfix-ctl's printed lines: the devices' health of an AgentState and a Telemetry.
#include "tools/ctl/message_text.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace kapfix::ctl {
namespace {

using ::testing::HasSubstr;

TEST(CtlMessageTextTest, StatusSaysWhichDeviceIsWaitingAndWhy) {
  kapfix::v1::AgentState state;
  state.mutable_camera_health()->set_status(kapfix::v1::DEVICE_WAITING);
  state.mutable_camera_health()->set_reason("cannot open /dev/video0");
  state.mutable_servo_health()->set_status(kapfix::v1::DEVICE_OK);
  const std::string text = StateText(state);
  EXPECT_THAT(text, HasSubstr("\ncamera: waiting reason=cannot open /dev/video0\n"));
  EXPECT_THAT(text, HasSubstr("\nservos: ok\n"));
}

TEST(CtlMessageTextTest, AnAgentThatDoesNotReportItsDevicesPrintsUnknown) {
  EXPECT_THAT(StateText(kapfix::v1::AgentState{}), HasSubstr("\ncamera: unknown\n"));
}

TEST(CtlMessageTextTest, TelemetrySaysTheDevicesStatus) {
  kapfix::v1::Telemetry telemetry;
  telemetry.mutable_camera_health()->set_status(kapfix::v1::DEVICE_OK);
  telemetry.mutable_servo_health()->set_status(kapfix::v1::DEVICE_LOST);
  EXPECT_THAT(TelemetryText(telemetry), HasSubstr(" camera=ok servos=lost"));
}

}  // namespace
}  // namespace kapfix::ctl
