#include "agent/config/servo_config.hpp"

#include <spdlog/fmt/fmt.h>

#include <cmath>

#include "agent/servo/maestro_protocol.hpp"

namespace kapfix::agent {

std::optional<ServoBackend> ParseServoBackend(std::string_view text) {
  if (text == "sim") return ServoBackend::kSim;
  if (text == "maestro") return ServoBackend::kMaestro;
  if (text == "pca9685") return ServoBackend::kPca9685;
  return std::nullopt;
}

std::string_view ToString(ServoBackend backend) {
  switch (backend) {
    case ServoBackend::kSim:
      return "sim";
    case ServoBackend::kMaestro:
      return "maestro";
    case ServoBackend::kPca9685:
      return "pca9685";
  }
  return "?";
}

namespace {

bool AxisIsValid(const ServoAxisConfig& axis, const char* name, std::string* error) {
  std::string reason;
  if (!axis.limits.IsValid(&reason)) {
    if (error) *error = std::string("servo.") + name + ": " + reason;
    return false;
  }
  if (!axis.mapping.IsValid(maestro::kMaxChannels, &reason)) {
    if (error) *error = std::string("servo.") + name + ": " + reason;
    return false;
  }
  if (!(axis.play_deg >= 0 && axis.play_deg <= kMaxServoPlayDeg)) {
    if (error) {
      *error = fmt::format("servo.{}: play_deg must be 0…{:g} deg, got {:g}", name,
                           kMaxServoPlayDeg, axis.play_deg);
    }
    return false;
  }
  const ServoChannelMapping& m = axis.mapping;
  const double a = m.center_us + axis.limits.min_deg * m.us_per_deg;
  const double b = m.center_us + axis.limits.max_deg * m.us_per_deg;
  if (std::min(a, b) < m.min_us || std::max(a, b) > m.max_us) {
    if (error) {
      *error = fmt::format(
          "servo.{}: limits [{:g}, {:g}] deg need pulses {:g}…{:g} µs, outside [min_us, "
          "max_us] = [{:g}, {:g}] µs",
          name, axis.limits.min_deg, axis.limits.max_deg, std::min(a, b), std::max(a, b), m.min_us,
          m.max_us);
    }
    return false;
  }
  return true;
}

}  // namespace

bool ServoConfig::IsValid(std::string* error) const {
  if (!AxisIsValid(pan, "pan", error) || !AxisIsValid(tilt, "tilt", error)) return false;
  if (maestro_timeout_ms < 10 || maestro_timeout_ms > 60000 || maestro_timeout_ms % 10 != 0) {
    if (error) {
      *error =
          "servo.maestro_timeout_ms: must be 10…60000 ms in 10 ms steps (the Maestro's "
          "resolution), got " +
          std::to_string(maestro_timeout_ms);
    }
    return false;
  }
  std::string reason;
  if (backend == ServoBackend::kMaestro && !ToMaestroOptions().IsValid(&reason)) {
    if (error) *error = "servo: " + reason;
    return false;
  }
  if (backend == ServoBackend::kPca9685 && !ToPca9685Options().IsValid(&reason)) {
    if (error) *error = "servo: " + reason;
    return false;
  }
  return true;
}

MaestroServoDriverOptions ServoConfig::ToMaestroOptions() const {
  MaestroServoDriverOptions o;
  if (!device.empty()) o.device = device;
  o.baud = baud;
  o.pan = pan.mapping;
  o.tilt = tilt.mapping;
  o.serial_timeout_ms = maestro_timeout_ms;
  o.pan_home_deg = pan.limits.park_deg;
  o.tilt_home_deg = tilt.limits.park_deg;
  o.pan_max_rate_deg_per_s = pan.limits.max_rate_deg_per_s;
  o.tilt_max_rate_deg_per_s = tilt.limits.max_rate_deg_per_s;
  return o;
}

Pca9685ServoDriverOptions ServoConfig::ToPca9685Options() const {
  Pca9685ServoDriverOptions o;
  if (!device.empty()) o.device = device;
  o.address = i2c_address;
  o.pwm_hz = pwm_hz;
  o.oscillator_hz = oscillator_hz;
  o.pan = pan.mapping;
  o.tilt = tilt.mapping;
  return o;
}

}  // namespace kapfix::agent
