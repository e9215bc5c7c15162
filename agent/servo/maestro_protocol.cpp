#include "agent/servo/maestro_protocol.hpp"

#include <algorithm>
#include <cmath>

namespace kapfix::agent::maestro {

int QuarterMicroseconds(double pulse_us) {
  if (std::isnan(pulse_us)) return 0;
  const double quarters = std::clamp(std::round(pulse_us * 4.0), 0.0, double{kMaxTarget});
  return static_cast<int>(quarters);
}

std::array<std::uint8_t, 4> SetTargetCommand(int channel, int target_quarter_us) {
  const int target = std::clamp(target_quarter_us, 0, kMaxTarget);
  return {kSetTarget, static_cast<std::uint8_t>(channel & 0x7F),
          static_cast<std::uint8_t>(target & 0x7F),
          static_cast<std::uint8_t>((target >> 7) & 0x7F)};
}

namespace {

std::array<std::uint8_t, 4> SevenBitCommand(std::uint8_t command, int channel, int value) {
  return {command, static_cast<std::uint8_t>(channel & 0x7F),
          static_cast<std::uint8_t>(value & 0x7F), static_cast<std::uint8_t>((value >> 7) & 0x7F)};
}

}  // namespace

std::array<std::uint8_t, 4> SetSpeedCommand(int channel, int speed) {
  return SevenBitCommand(kSetSpeed, channel, std::clamp(speed, 0, kMaxTarget));
}

std::array<std::uint8_t, 4> SetAccelerationCommand(int channel, int acceleration) {
  return SevenBitCommand(kSetAcceleration, channel, std::clamp(acceleration, 0, 255));
}

int SpeedForRate(double deg_per_s, double us_per_deg) {
  // [deg/s] · [µs/deg] · 4 [¼ µs/µs] · 0.01 [s per 10 ms].
  const double speed = std::abs(deg_per_s * us_per_deg) * 4.0 * 0.01;
  if (!std::isfinite(speed)) return kMaxTarget;
  return std::clamp(static_cast<int>(std::floor(speed)), 1, kMaxTarget);
}

std::uint16_t ErrorRegister(std::uint8_t low, std::uint8_t high) {
  return static_cast<std::uint16_t>(low | (high << 8));
}

std::string DescribeErrors(std::uint16_t errors) {
  static const char* const kNames[] = {
      "serial signal error", "serial overrun error",    "serial buffer full",
      "serial CRC error",    "serial protocol error",   "serial timeout",
      "script stack error",  "script call stack error", "script program counter error",
  };
  if (errors == 0) return "none";
  std::string text;
  for (int bit = 0; bit < 16; ++bit) {
    if (!(errors & (1u << bit))) continue;
    if (!text.empty()) text += ", ";
    text += bit < 9 ? std::string(kNames[bit]) : std::string("unknown error");
    text += " (bit " + std::to_string(bit) + ")";
  }
  return text;
}

}  // namespace kapfix::agent::maestro
