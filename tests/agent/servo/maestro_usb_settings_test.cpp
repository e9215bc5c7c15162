#include "agent/servo/maestro_usb_settings.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace kapfix::agent {
namespace {

// Expected bytes from Pololu's USB SDK (Maestro/Usc/Usc.cs, Usc_protocol.cs):
// set parameter = vendor OUT 0x40, request 0x82, wValue = value, wIndex = size << 8 | id;
// get parameter = vendor IN 0xC0, request 0x81, wValue 0, wIndex = id, wLength = size;
// serial timeout = parameter 6, 2 B, 10 ms units; channel c's home = 30 + 9·c, 2 B,
// quarter-µs; reinitialize = 0x40, 0x90, 0, 0.

MaestroUsbSettings Settings() {
  MaestroUsbSettings settings;
  settings.serial_timeout_ms = 500;
  settings.homes = {{.channel = 0, .home_quarter_us = 6000},
                    {.channel = 5, .home_quarter_us = 5500}};
  return settings;
}

TEST(MaestroUsbSettingsTest, TransfersAreTheExactSetupPackets) {
  const std::vector<MaestroControlTransfer> expected = {
      {.request_type = 0x40, .request = 0x82, .value = 50, .index = 0x0206, .length = 0},
      {.request_type = 0x40, .request = 0x82, .value = 6000, .index = 0x021E, .length = 0},
      {.request_type = 0x40, .request = 0x82, .value = 5500, .index = 0x024B, .length = 0},
      {.request_type = 0x40, .request = 0x90, .value = 0, .index = 0, .length = 0},
  };
  EXPECT_EQ(MaestroSettingsTransfers(Settings()), expected);
}

TEST(MaestroUsbSettingsTest, ReadBackIsAGetParameterOfTheSameSize) {
  const auto parameters = MaestroSettingsParameters(Settings());
  ASSERT_EQ(parameters.size(), 3u);
  EXPECT_EQ(GetParameterTransfer(parameters[0]),
            (MaestroControlTransfer{
                .request_type = 0xC0, .request = 0x81, .value = 0, .index = 6, .length = 2}));
  EXPECT_EQ(GetParameterTransfer(parameters[2]),
            (MaestroControlTransfer{
                .request_type = 0xC0, .request = 0x81, .value = 0, .index = 75, .length = 2}));
}

TEST(MaestroUsbSettingsTest, LastChannelOfAMiniMaestro24HasParameter237) {
  MaestroUsbSettings settings;
  settings.homes = {{.channel = 23, .home_quarter_us = 4000}};
  const auto transfers = MaestroSettingsTransfers(settings);
  ASSERT_EQ(transfers.size(), 3u);
  EXPECT_EQ(transfers[1].index, 0x02ED);  // 30 + 9 · 23 = 237
  EXPECT_EQ(transfers[1].value, 4000);
}

TEST(MaestroUsbSettingsTest, TimeoutIsRoundedToTenMillisecondSteps) {
  MaestroUsbSettings settings;
  settings.serial_timeout_ms = 304;
  EXPECT_EQ(MaestroSettingsParameters(settings).front().value, 30);
  settings.serial_timeout_ms = 655350;
  EXPECT_EQ(MaestroSettingsParameters(settings).front().value, 0xFFFF);
}

TEST(MaestroUsbSettingsTest, NothingToWriteSendsNoReinitialize) {
  EXPECT_TRUE(MaestroSettingsTransfers(std::vector<MaestroParameter>{}).empty());
}

TEST(MaestroUsbSettingsTest, ParameterValueIsLittleEndian) {
  EXPECT_EQ(ParameterValue({0x70, 0x17}), 6000);
  EXPECT_EQ(ParameterValue({0x32}), 50);
  EXPECT_EQ(ParameterValue({}), 0);
}

TEST(MaestroUsbSettingsTest, ValuesAreDescribedInTheirUnits) {
  const auto parameters = MaestroSettingsParameters(Settings());
  EXPECT_EQ(DescribeParameterValue(parameters[0], 50), "500 ms (50)");
  EXPECT_EQ(DescribeParameterValue(parameters[0], 0), "off (0)");
  EXPECT_EQ(DescribeParameterValue(parameters[1], 6000), "1500 µs (6000)");
  EXPECT_EQ(DescribeParameterValue(parameters[1], 6001), "1500.25 µs (6001)");
  EXPECT_EQ(DescribeParameterValue(parameters[1], 1), "ignore (1)");
}

TEST(MaestroUsbSettingsTest, InvalidSettingsAreNamed) {
  std::string error;
  MaestroUsbSettings settings = Settings();
  settings.serial_timeout_ms = 0;
  EXPECT_FALSE(settings.IsValid(&error));
  EXPECT_NE(error.find("serial timeout"), std::string::npos) << error;
  settings = Settings();
  settings.homes[1].channel = 0;
  EXPECT_FALSE(settings.IsValid(&error));
  EXPECT_NE(error.find("twice"), std::string::npos) << error;
  settings = Settings();
  settings.homes[0].home_quarter_us = 1;  // would mean Ignore
  EXPECT_FALSE(settings.IsValid(&error));
  settings = Settings();
  settings.homes[0].channel = 24;
  EXPECT_FALSE(settings.IsValid(&error));
  EXPECT_TRUE(Settings().IsValid(&error)) << error;
}

TEST(MaestroUsbSettingsTest, ProductIdsGiveTheChannelCount) {
  EXPECT_EQ(maestro::ChannelCount(0x0089), 6);
  EXPECT_EQ(maestro::ChannelCount(0x008A), 12);
  EXPECT_EQ(maestro::ChannelCount(0x008B), 18);
  EXPECT_EQ(maestro::ChannelCount(0x008C), 24);
  EXPECT_EQ(maestro::ChannelCount(0x0088), 0);  // a Maestro's bootloader
}

}  // namespace
}  // namespace kapfix::agent
