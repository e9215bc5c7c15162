#include "agent/servo/pca9685_registers.hpp"

#include <algorithm>
#include <cmath>

namespace kapfix::agent::pca9685 {

int PreScale(double oscillator_hz, double pwm_hz) {
  const double raw = std::round(oscillator_hz / (kTicksPerPeriod * pwm_hz)) - 1.0;
  if (std::isnan(raw)) return kMaxPreScale;
  return static_cast<int>(std::clamp(raw, double{kMinPreScale}, double{kMaxPreScale}));
}

double FrequencyHz(double oscillator_hz, int prescale) {
  return oscillator_hz / (kTicksPerPeriod * (prescale + 1.0));
}

int PulseTicks(double pulse_us, double oscillator_hz, int prescale) {
  const double ticks = std::round(pulse_us * 1e-6 * oscillator_hz / (prescale + 1.0));
  if (std::isnan(ticks)) return 0;
  return static_cast<int>(std::clamp(ticks, 0.0, double{kTicksPerPeriod - 1}));
}

double TicksPulseUs(int ticks, double oscillator_hz, int prescale) {
  return ticks * (prescale + 1) / oscillator_hz * 1e6;
}

std::array<std::uint8_t, 5> ChannelPulseWrite(int channel, int off_ticks) {
  const int off = std::clamp(off_ticks, 0, kTicksPerPeriod - 1);
  return {static_cast<std::uint8_t>(kLed0OnL + 4 * channel), 0x00, 0x00,
          static_cast<std::uint8_t>(off & 0xFF), static_cast<std::uint8_t>((off >> 8) & 0x0F)};
}

std::vector<RegisterWrite> InitSequence(int prescale) {
  const auto p = static_cast<std::uint8_t>(std::clamp(prescale, kMinPreScale, kMaxPreScale));
  return {
      {kMode1, static_cast<std::uint8_t>(kMode1Sleep | kMode1AutoIncrement), 0},
      {kPreScale, p, 0},
      {kMode2, kMode2OutDrv, 0},
      {kMode1, kMode1AutoIncrement, 500},
      {kMode1, static_cast<std::uint8_t>(kMode1Restart | kMode1AutoIncrement), 0},
  };
}

}  // namespace kapfix::agent::pca9685
