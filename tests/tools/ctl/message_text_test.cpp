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

TEST(CtlMessageTextTest, TelemetrySaysTheOnlineCalibrationWhenThereIsOne) {
  kapfix::v1::Telemetry telemetry;
  EXPECT_THAT(TelemetryText(telemetry), ::testing::Not(HasSubstr("deg_per_px=")));
  telemetry.mutable_deg_per_px()->set_pan_deg_per_px(0.25f);
  telemetry.mutable_deg_per_px()->set_tilt_deg_per_px(0.5f);
  telemetry.mutable_deg_per_px()->set_pan_uncertainty(0.125f);
  telemetry.mutable_deg_per_px()->set_trusted(true);
  telemetry.set_forecast_weight(0.75f);
  EXPECT_THAT(TelemetryText(telemetry),
              HasSubstr(" deg_per_px=0.25/0.5 uncertainty=0.125/0 deg_per_px_trusted=1 "
                        "forecast_weight=0.75"));
}

}  // namespace
}  // namespace kapfix::ctl
