#include "agent/servo/maestro_protocol.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>

namespace kapfix::agent::maestro {
namespace {

using Bytes = std::array<std::uint8_t, 4>;

TEST(MaestroProtocolTest, SetTargetMatchesThePololuManualExample) {
  // User's Guide §5.e: channel 0 to 1500 µs → 0x84, 0x00, 0x70, 0x2E.
  EXPECT_EQ(SetTargetCommand(0, 6000), (Bytes{0x84, 0x00, 0x70, 0x2E}));
}

TEST(MaestroProtocolTest, SetTargetSplitsTheTargetIntoTwo7BitBytes) {
  // 1375 µs = 5500 quarter-µs = 42 · 128 + 124.
  EXPECT_EQ(SetTargetCommand(5, 5500), (Bytes{0x84, 0x05, 0x7C, 0x2A}));
}

TEST(MaestroProtocolTest, QuarterMicrosecondsRoundsToNearest) {
  EXPECT_EQ(QuarterMicroseconds(1500.1), 6000);
  EXPECT_EQ(QuarterMicroseconds(1500.2), 6001);
}

TEST(MaestroProtocolTest, QuarterMicrosecondsClampsTo14Bits) {
  EXPECT_EQ(QuarterMicroseconds(1e9), 0x3FFF);
  EXPECT_EQ(QuarterMicroseconds(-5), 0);
}

TEST(MaestroProtocolTest, ErrorRegisterIsLowByteFirst) {
  EXPECT_EQ(ErrorRegister(0x20, 0x01), 0x0120);
}

TEST(MaestroProtocolTest, DescribeErrorsNamesTheSerialTimeoutBit) {
  EXPECT_EQ(DescribeErrors(kErrorSerialTimeout), "serial timeout (bit 5)");
}

TEST(MaestroProtocolTest, DescribeErrorsOfZeroIsNone) { EXPECT_EQ(DescribeErrors(0), "none"); }

}  // namespace
}  // namespace kapfix::agent::maestro
