#include "agent/servo/pca9685_registers.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>

namespace kapfix::agent::pca9685 {
namespace {

TEST(Pca9685RegistersTest, PreScaleFor50HzAt25MHzIs121) {
  // Datasheet §7.3.5: round(25 MHz / (4096 · 50 Hz)) − 1 = 121.
  EXPECT_EQ(PreScale(25e6, 50), 121);
}

TEST(Pca9685RegistersTest, PreScaleFor200HzIs30) {
  // Datasheet example: 200 Hz → 0x1E.
  EXPECT_EQ(PreScale(25e6, 200), 0x1E);
}

TEST(Pca9685RegistersTest, PreScaleIsClampedToTheHardwareRange) {
  EXPECT_EQ(PreScale(25e6, 10000), 3);
  EXPECT_EQ(PreScale(25e6, 1), 255);
}

TEST(Pca9685RegistersTest, FrequencyOfPreScale121Is50Point03Hz) {
  EXPECT_NEAR(FrequencyHz(25e6, 121), 50.0288, 1e-3);
}

TEST(Pca9685RegistersTest, CentrePulseIs307Ticks) {
  // 1500 µs / (122 / 25 MHz = 4.88 µs per tick) = 307.4.
  EXPECT_EQ(PulseTicks(1500, 25e6, 121), 307);
}

TEST(Pca9685RegistersTest, PulseTicksFollowTheOscillator) {
  // A chip running 4 % fast counts 4 % more ticks in the same pulse.
  EXPECT_EQ(PulseTicks(1500, 26e6, 121), 320);
}

TEST(Pca9685RegistersTest, PulseTicksAreClampedTo12Bits) {
  EXPECT_EQ(PulseTicks(1e6, 25e6, 121), 4095);
}

TEST(Pca9685RegistersTest, ChannelWriteStartsAtItsLedOnRegister) {
  // Channel 3: LED3_ON_L = 0x06 + 12 = 0x12; OFF = 307 = 0x133.
  EXPECT_EQ(ChannelPulseWrite(3, 307), (std::array<std::uint8_t, 5>{0x12, 0, 0, 0x33, 0x01}));
}

TEST(Pca9685RegistersTest, ChannelWriteOfChannel15IsAt0x42) {
  EXPECT_EQ(ChannelPulseWrite(15, 0)[0], 0x42);
}

TEST(Pca9685RegistersTest, InitWritesPreScaleWhileAsleep) {
  const auto steps = InitSequence(121);
  ASSERT_GE(steps.size(), 2u);
  EXPECT_EQ(steps[0].reg, kMode1);
  EXPECT_TRUE(steps[0].value & kMode1Sleep);
  EXPECT_EQ(steps[1].reg, kPreScale);
  EXPECT_EQ(steps[1].value, 121);
}

TEST(Pca9685RegistersTest, InitEndsAwakeWithAutoIncrement) {
  const auto steps = InitSequence(121);
  ASSERT_FALSE(steps.empty());
  EXPECT_EQ(steps.back().reg, kMode1);
  EXPECT_FALSE(steps.back().value & kMode1Sleep);
  EXPECT_TRUE(steps.back().value & kMode1AutoIncrement);
}

TEST(Pca9685RegistersTest, InitWaitsForTheOscillatorAfterWaking) {
  // Datasheet §7.3.1.1: 500 µs after clearing SLEEP before RESTART.
  const auto steps = InitSequence(121);
  int waited_us = 0;
  bool woke = false;
  for (const RegisterWrite& step : steps) {
    if (woke) break;
    if (step.reg == kMode1 && !(step.value & kMode1Sleep)) {
      woke = true;
      waited_us = step.wait_after_us;
    }
  }
  EXPECT_GE(waited_us, 500);
}

TEST(Pca9685RegistersTest, TicksBackToPulseInvertPulseTicksWithinOneTick) {
  const int prescale = PreScale(25e6, 50);
  for (const double pulse_us : {900.0, 1500.0, 2100.0}) {
    const int ticks = PulseTicks(pulse_us, 25e6, prescale);
    EXPECT_NEAR(TicksPulseUs(ticks, 25e6, prescale), pulse_us, 4.88 / 2 + 1e-9);
  }
}

}  // namespace
}  // namespace kapfix::agent::pca9685
