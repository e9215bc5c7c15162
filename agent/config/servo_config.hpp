#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "agent/servo/maestro_servo_driver.hpp"
#include "agent/servo/pca9685_servo_driver.hpp"
#include "agent/servo/servo_channel_mapping.hpp"
#include "common/control/servo_belief.hpp"
#include "common/control/servo_limits.hpp"

namespace kapfix::agent {

enum class ServoBackend {
  kSim,      // simulated servos (SPEC §3)
  kMaestro,  // Pololu Maestro, serial
  kPca9685,  // PCA9685, Linux I2C
};

std::optional<ServoBackend> ParseServoBackend(std::string_view text);  // sim|maestro|pca9685
std::string_view ToString(ServoBackend backend);

// One axis: where its pulses go and what it may do.
struct ServoAxisConfig {
  ServoChannelMapping mapping;
  ServoLimits limits;
  // [deg] the servo's play (backlash): how far its shaft turns back before the output
  // follows. The servo belief drags the output behind the shaft through it; taken as 0 on a
  // servo that has play, the belief is off by half the play on almost every frame. 0…10
  // (kMaxServoPlayDeg). Under --sim the simulated servos' own play is used instead.
  double play_deg = 0;
};

// The "servo" section. Defaults: resources/README.md.
struct ServoConfig {
  ServoBackend backend = ServoBackend::kSim;
  std::string device;  // "" = /dev/ttyACM0 (maestro) or /dev/i2c-1 (pca9685)
  int baud = 115200;   // [bit/s] maestro
  // [ms] maestro: its serial timeout, set over USB at start-up; with no command for this
  // long it sends pan and tilt to park_deg. 10…60000 in 10 ms steps; AgentConfig checks
  // frame period < it ≤ watchdog_ms.
  int maestro_timeout_ms = 500;
  int i2c_address = 0x40;       // pca9685
  double pwm_hz = 50;           // [Hz] pca9685
  double oscillator_hz = 25e6;  // [Hz] pca9685
  ServoAxisConfig pan{.mapping = {.channel = 0}, .limits = {}};
  ServoAxisConfig tilt{.mapping = {.channel = 1}, .limits = {}};

  // Also checks that each axis's [min_deg, max_deg] maps to pulses inside [min_us, max_us]:
  // otherwise the pulse clamp, not the limits, would stop the servo.
  bool IsValid(std::string* error) const;

  MaestroServoDriverOptions ToMaestroOptions() const;
  Pca9685ServoDriverOptions ToPca9685Options() const;
};

}  // namespace kapfix::agent
