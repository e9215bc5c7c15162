// DeviceHealth: the reason a link message carries is short and valid UTF-8 whatever the
// device's error text was; the status line says both devices.
#include "agent/pipeline/device_health.hpp"

#include <gtest/gtest.h>

#include <string>

namespace kapfix::agent {
namespace {

bool ValidUtf8(const std::string& text) { return BoundedUtf8(text, text.size()) == text; }

TEST(DeviceHealthTest, AShortReasonIsKeptAsItIs) {
  EXPECT_EQ(DeviceHealth::Waiting("cannot open /dev/video0: No such file").reason,
            "cannot open /dev/video0: No such file");
}

TEST(DeviceHealthTest, ALongReasonIsCutToTheBound) {
  const DeviceHealth health = DeviceHealth::Lost(std::string(1000, 'x'));
  EXPECT_EQ(health.status, DeviceStatus::kLost);
  EXPECT_EQ(health.reason, std::string(kMaxDeviceReasonBytes, 'x'));
}

TEST(DeviceHealthTest, TheCutNeverSplitsACharacter) {
  // "é" is two bytes: 159 bytes of 'a' leave room for one byte only, so "é" goes whole.
  const std::string reason = std::string(kMaxDeviceReasonBytes - 1, 'a') + "\xC3\xA9";
  const DeviceHealth health = DeviceHealth::Waiting(reason);
  EXPECT_EQ(health.reason, std::string(kMaxDeviceReasonBytes - 1, 'a'));
  EXPECT_TRUE(ValidUtf8(health.reason));
}

TEST(DeviceHealthTest, InvalidBytesBecomeQuestionMarks) {
  // A device path in Latin-1 ("/dev/caméra"), a lone continuation byte, an overlong '/'.
  EXPECT_EQ(BoundedUtf8("/dev/cam\xE9ra", 100), "/dev/cam?ra");
  EXPECT_EQ(BoundedUtf8("a\x80z", 100), "a?z");
  EXPECT_EQ(BoundedUtf8("\xC0\xAF", 100), "??");
  EXPECT_EQ(BoundedUtf8("caméra ✓", 100), "caméra ✓");
}

TEST(DeviceHealthTest, TheStatusLineSaysBothDevicesAndTheReason) {
  DevicesHealth health;
  health.camera = DeviceHealth::Waiting("no camera 127.0.0.1");
  EXPECT_EQ(StatusLine(health), "camera waiting: no camera 127.0.0.1; servos ok");
}

}  // namespace
}  // namespace kapfix::agent
