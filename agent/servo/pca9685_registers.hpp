#pragma once

#include <array>
#include <cstdint>
#include <vector>

// The PCA9685's register arithmetic (NXP PCA9685 datasheet, rev. 4), as pure functions so
// that it can be tested without an I2C bus.
namespace kapfix::agent::pca9685 {

inline constexpr std::uint8_t kMode1 = 0x00;
inline constexpr std::uint8_t kMode2 = 0x01;
inline constexpr std::uint8_t kLed0OnL = 0x06;  // LEDn_ON_L = 0x06 + 4n, then ON_H, OFF_L, OFF_H
inline constexpr std::uint8_t kPreScale = 0xFE;

inline constexpr std::uint8_t kMode1Restart = 0x80;
inline constexpr std::uint8_t kMode1AutoIncrement = 0x20;  // register pointer advances per byte
inline constexpr std::uint8_t kMode1Sleep = 0x10;          // oscillator off; PRE_SCALE writable
inline constexpr std::uint8_t kMode2OutDrv = 0x04;         // totem-pole outputs (servo signal)

inline constexpr int kChannels = 16;
inline constexpr int kTicksPerPeriod = 4096;  // 12-bit counter
inline constexpr double kInternalOscillatorHz = 25e6;
inline constexpr int kMinPreScale = 3;  // hardware floor (≈1526 Hz at 25 MHz)
inline constexpr int kMaxPreScale = 255;

// PRE_SCALE = round(oscillator / (4096 · pwm)) − 1, clamped to 3…255 (§7.3.5).
// 25 MHz, 50 Hz → 121.
int PreScale(double oscillator_hz, double pwm_hz);

// The PWM frequency a prescale really gives: oscillator / (4096 · (prescale + 1)) [Hz].
// 25 MHz, 121 → 50.03 Hz.
double FrequencyHz(double oscillator_hz, int prescale);

// Counter ticks for a pulse [µs] at that prescale, rounded and clamped to 0…4095 (one tick is
// (prescale + 1) / oscillator: 4.88 µs at 25 MHz, 121). 1500 µs → 307.
int PulseTicks(double pulse_us, double oscillator_hz, int prescale);

// The inverse of PulseTicks: a pulse of `ticks` counter ticks [µs]. 307 at 25 MHz, 121 → 1499.
double TicksPulseUs(int ticks, double oscillator_hz, int prescale);

// One I2C write starting at LEDn_ON_L with auto-increment: register, ON_L, ON_H, OFF_L,
// OFF_H. Pulses start at tick 0 (ON = 0) and end at `off_ticks`.
std::array<std::uint8_t, 5> ChannelPulseWrite(int channel, int off_ticks);

// A register write, and how long to wait after it [µs].
struct RegisterWrite {
  std::uint8_t reg;
  std::uint8_t value;
  int wait_after_us;
};

// Start-up: sleep (PRE_SCALE is only writable then), set PRE_SCALE, totem-pole outputs, wake
// with auto-increment, wait the 500 µs the oscillator needs, then restart the PWM channels.
std::vector<RegisterWrite> InitSequence(int prescale);

}  // namespace kapfix::agent::pca9685
