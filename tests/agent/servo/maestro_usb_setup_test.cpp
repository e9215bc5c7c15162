#include "agent/servo/maestro_usb_setup.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "tests/agent/support/fake_maestro_usb_port.hpp"

namespace kapfix::agent {
namespace {

MaestroUsbSettings Settings() {
  MaestroUsbSettings settings;
  settings.serial_timeout_ms = 300;
  settings.homes = {{.channel = 0, .home_quarter_us = 6000},
                    {.channel = 1, .home_quarter_us = 5800}};
  return settings;
}

int Count(const FakeMaestroUsbPort::State& state, std::uint8_t request) {
  return static_cast<int>(
      std::count_if(state.transfers.begin(), state.transfers.end(),
                    [request](const MaestroControlTransfer& t) { return t.request == request; }));
}

TEST(MaestroUsbSetupTest, FactorySettingsAreWrittenReinitializedAndVerified) {
  FakeMaestroUsbPort::State state;  // factory: timeout off, homes off, UART detect baud rate
  FakeMaestroUsbPort port(&state);
  const MaestroUsbSetupResult result = ApplyMaestroUsbSettings(port, Settings());
  EXPECT_TRUE(result.ok) << result.message;
  EXPECT_TRUE(result.changed);
  EXPECT_EQ(state.eeprom[6], 30);
  EXPECT_EQ(state.eeprom[30], 6000);
  EXPECT_EQ(state.eeprom[39], 5800);
  EXPECT_EQ(state.eeprom[maestro::kParameterSerialMode], maestro::kSerialModeUsbDualPort);
  EXPECT_EQ(Count(state, maestro::kRequestSetParameter), 4);
  EXPECT_EQ(Count(state, maestro::kRequestReinitialize), 1);
  // 4 before and 4 after writing, then each channel's Min and Max.
  EXPECT_EQ(Count(state, maestro::kRequestGetParameter), 12);
  EXPECT_FALSE(state.open);  // closed again
  EXPECT_NE(result.message.find("serial timeout 300 ms (30)"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("channel 1 home off (0) → 1450 µs (5800)"), std::string::npos)
      << result.message;
  EXPECT_NE(result.message.find("verified"), std::string::npos) << result.message;
}

TEST(MaestroUsbSetupTest, EachChannelsOwnMinAndMaxAreReadInMicroseconds) {
  FakeMaestroUsbPort::State state;
  state.eeprom[maestro::kParameterServo0Max + 9] = 150;  // channel 1 Max 2400 µs
  FakeMaestroUsbPort port(&state);
  const MaestroUsbSetupResult result = ApplyMaestroUsbSettings(port, Settings());
  ASSERT_TRUE(result.ok) << result.message;
  ASSERT_EQ(result.ranges.size(), 2u);
  EXPECT_EQ(result.ranges[0].channel, 0);
  EXPECT_DOUBLE_EQ(result.ranges[0].min_us, 992);
  EXPECT_DOUBLE_EQ(result.ranges[0].max_us, 2000);
  EXPECT_EQ(result.ranges[1].channel, 1);
  EXPECT_DOUBLE_EQ(result.ranges[1].max_us, 2400);
}

TEST(MaestroUsbSetupTest, MatchingSettingsAreNotRewritten) {
  FakeMaestroUsbPort::State state;
  state.eeprom = {{6, 30}, {30, 6000}, {39, 5800}};
  FakeMaestroUsbPort port(&state);
  const MaestroUsbSetupResult result = ApplyMaestroUsbSettings(port, Settings());
  EXPECT_TRUE(result.ok) << result.message;
  EXPECT_FALSE(result.changed);
  EXPECT_EQ(Count(state, maestro::kRequestSetParameter), 0);
  EXPECT_EQ(Count(state, maestro::kRequestReinitialize), 0);
  EXPECT_NE(result.message.find("already set"), std::string::npos) << result.message;
}

TEST(MaestroUsbSetupTest, OnlyDifferingParametersAreWritten) {
  FakeMaestroUsbPort::State state;
  state.eeprom = {{6, 30}, {30, 6000}, {39, 6000}};
  FakeMaestroUsbPort port(&state);
  EXPECT_TRUE(ApplyMaestroUsbSettings(port, Settings()).ok);
  ASSERT_EQ(Count(state, maestro::kRequestSetParameter), 1);
  const auto write = std::find_if(
      state.transfers.begin(), state.transfers.end(),
      [](const MaestroControlTransfer& t) { return t.request == maestro::kRequestSetParameter; });
  EXPECT_EQ(write->index, 0x0227);  // 2 bytes, parameter 39 = channel 1 home
  EXPECT_EQ(write->value, 5800);
}

TEST(MaestroUsbSetupTest, ReadBackMismatchIsAFailureNamingTheParameter) {
  FakeMaestroUsbPort::State state;
  state.drop_writes = true;
  FakeMaestroUsbPort port(&state);
  const MaestroUsbSetupResult result = ApplyMaestroUsbSettings(port, Settings());
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.message.find("serial timeout reads back as off (0) after writing 300 ms"),
            std::string::npos)
      << result.message;
  EXPECT_NE(result.message.find("Control Center"), std::string::npos) << result.message;
  EXPECT_FALSE(state.open);
}

TEST(MaestroUsbSetupTest, NoDeviceIsAFailureWithTheCauseAndTheManualValues) {
  FakeMaestroUsbPort::State state;
  state.open_error = "no Maestro found on USB";
  FakeMaestroUsbPort port(&state);
  const MaestroUsbSetupResult result = ApplyMaestroUsbSettings(port, Settings());
  EXPECT_FALSE(result.ok);
  EXPECT_TRUE(state.transfers.empty());
  EXPECT_NE(result.message.find("no Maestro found on USB"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("Timeout = 0.30 s"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("channel 1 \"On startup or error\" = Go to 1450 µs"),
            std::string::npos)
      << result.message;
  EXPECT_NE(result.message.find("Flying on"), std::string::npos) << result.message;
}

TEST(MaestroUsbSetupTest, RefusedWriteIsAFailure) {
  FakeMaestroUsbPort::State state;
  state.refuse_writes = true;
  FakeMaestroUsbPort port(&state);
  const MaestroUsbSetupResult result = ApplyMaestroUsbSettings(port, Settings());
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.message.find("cannot write a parameter"), std::string::npos) << result.message;
  EXPECT_EQ(Count(state, maestro::kRequestReinitialize), 0);
}

TEST(MaestroUsbSetupTest, ChannelBeyondTheMaestroIsAFailure) {
  FakeMaestroUsbPort::State state;
  state.product_id = maestro::kProductMicro6;
  FakeMaestroUsbPort port(&state);
  MaestroUsbSettings settings = Settings();
  settings.homes[1].channel = 8;
  const MaestroUsbSetupResult result = ApplyMaestroUsbSettings(port, settings);
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.message.find("it has 6 channels, no channel 8"), std::string::npos)
      << result.message;
  EXPECT_EQ(Count(state, maestro::kRequestSetParameter), 0);
}

}  // namespace
}  // namespace kapfix::agent
