#pragma once

#include <array>
#include <cstdint>
#include <string>

// The parts of the Pololu Maestro's compact serial protocol that the agent uses, as pure
// functions (Pololu Maestro Servo Controller User's Guide, §5.e "Serial Servo Commands").
// Command bytes have their top bit set; data bytes carry 7 bits each.
namespace kapfix::agent::maestro {

inline constexpr std::uint8_t kSetTarget = 0x84;  // channel, target low 7 bits, high 7 bits
inline constexpr std::uint8_t kSetSpeed = 0x87;   // channel, speed low 7, high 7 [¼ µs / 10 ms]
inline constexpr std::uint8_t kSetAcceleration = 0x89;  // channel, low 7, high 7
                                                        // [¼ µs / 10 ms / 80 ms], 0…255
inline constexpr std::uint8_t kGetPosition = 0x90;      // channel; answers 2 bytes [quarter-µs]
inline constexpr std::uint8_t kGetErrors = 0xA1;  // answers 2 bytes, low then high; clears them
inline constexpr int kMaxChannels = 24;           // Mini Maestro 24; Micro Maestro has 6
inline constexpr int kMaxTarget = 0x3FFF;         // 14 bits [quarter-µs]

// Error register bits (User's Guide §4.e). Any error sends the servos to their home
// positions ("On startup or error" in the Control Center), except channels set to Ignore.
inline constexpr std::uint16_t kErrorSerialTimeout = 1u << 5;

// Pulse [µs] → target [quarter-µs], rounded and clamped to 0…kMaxTarget.
int QuarterMicroseconds(double pulse_us);

// The 4 bytes of Set Target: 0x84, channel, target & 0x7F, (target >> 7) & 0x7F.
// Example (User's Guide): channel 0 to 1500 µs = 6000 quarter-µs → 84 00 70 2E.
std::array<std::uint8_t, 4> SetTargetCommand(int channel, int target_quarter_us);

// Set Speed / Set Acceleration: command, channel, value & 0x7F, (value >> 7) & 0x7F. Speed
// 0 = unlimited; the value is clamped to 0…kMaxTarget (acceleration to 0…255).
std::array<std::uint8_t, 4> SetSpeedCommand(int channel, int speed);
std::array<std::uint8_t, 4> SetAccelerationCommand(int channel, int acceleration);
// The speed [¼ µs / 10 ms] that moves a servo at most `deg_per_s` through `us_per_deg`,
// rounded down (never faster than asked), at least 1.
int SpeedForRate(double deg_per_s, double us_per_deg);

// Get Errors' answer (low byte first) → the 16-bit error register.
std::uint16_t ErrorRegister(std::uint8_t low, std::uint8_t high);

// "serial timeout (bit 5), serial protocol error (bit 4)", or "none".
std::string DescribeErrors(std::uint16_t errors);

}  // namespace kapfix::agent::maestro
