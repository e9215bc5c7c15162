#include "agent/servo/pca9685_servo_driver.hpp"

#include <fcntl.h>
#include <linux/i2c-dev.h>
#include <spdlog/spdlog.h>
#include <sys/ioctl.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <thread>

#include "agent/servo/pca9685_registers.hpp"

namespace kapfix::agent {
namespace {

std::string Hex(int value) {
  char text[8];
  std::snprintf(text, sizeof(text), "0x%02x", value);
  return text;
}

}  // namespace

bool Pca9685ServoDriverOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (device.empty()) return fail("PCA9685 device path is empty");
  if (address < 0x40 || address > 0x7F) {
    return fail("PCA9685 address must be 0x40…0x7f, got " + Hex(address));
  }
  if (!std::isfinite(oscillator_hz) || oscillator_hz < 1e6 || oscillator_hz > 50e6) {
    return fail("PCA9685 oscillator_hz must be 1e6…50e6 Hz, got " + std::to_string(oscillator_hz));
  }
  if (!std::isfinite(pwm_hz) || pwm_hz < 24 || pwm_hz > 1526) {
    return fail("PCA9685 pwm_hz must be 24…1526 Hz, got " + std::to_string(pwm_hz));
  }
  std::string reason;
  if (!pan.IsValid(pca9685::kChannels, &reason)) return fail("PCA9685 pan: " + reason);
  if (!tilt.IsValid(pca9685::kChannels, &reason)) return fail("PCA9685 tilt: " + reason);
  if (pan.channel == tilt.channel) return fail("PCA9685 pan and tilt use the same channel");
  const double period_us =
      1e6 / pca9685::FrequencyHz(oscillator_hz, pca9685::PreScale(oscillator_hz, pwm_hz));
  if (pan.max_us >= period_us || tilt.max_us >= period_us) {
    return fail("PCA9685 max_us must be shorter than the PWM period of " +
                std::to_string(period_us) + " µs");
  }
  return true;
}

Pca9685ServoDriver::Pca9685ServoDriver(Pca9685ServoDriverOptions options)
    : options_(std::move(options)) {}

Pca9685ServoDriver::~Pca9685ServoDriver() { Close(); }

void Pca9685ServoDriver::Close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool Pca9685ServoDriver::Fail(const std::string& reason, std::string* error) const {
  if (error)
    *error = "PCA9685 at " + Hex(options_.address) + " on " + options_.device + ": " + reason;
  return false;
}

bool Pca9685ServoDriver::WriteBytes(const std::uint8_t* bytes, std::size_t count,
                                    std::string* error) {
  if (fd_ < 0) return Fail("not open", error);
  // An I2C message cannot be split: one write() is one transfer, all or nothing.
  const ssize_t written = ::write(fd_, bytes, count);
  if (written == static_cast<ssize_t>(count)) return true;
  const int code = errno;
  if (written < 0 && (code == ENXIO || code == EREMOTEIO)) {
    return Fail("no answer (" + std::string(std::strerror(code)) + "); wiring or address?", error);
  }
  return Fail(
      "write failed (" + std::string(written < 0 ? std::strerror(code) : "short write") + ")",
      error);
}

bool Pca9685ServoDriver::ReadRegister(std::uint8_t reg, std::uint8_t* value, std::string* error) {
  if (!WriteBytes(&reg, 1, error)) return false;
  if (::read(fd_, value, 1) != 1) {
    return Fail("read failed (" + std::string(std::strerror(errno)) + ")", error);
  }
  return true;
}

bool Pca9685ServoDriver::Open(std::string* error) {
  Close();
  std::string reason;
  if (!options_.IsValid(&reason)) return Fail(reason, error);
  fd_ = ::open(options_.device.c_str(), O_RDWR | O_CLOEXEC);
  if (fd_ < 0) {
    const int code = errno;
    std::string text = "cannot open (" + std::string(std::strerror(code)) + ")";
    if (code == ENOENT) text += "; is the i2c-dev module loaded and I2C enabled?";
    if (code == EACCES) text += "; is the agent's user in group i2c?";
    return Fail(text, error);
  }
  if (::ioctl(fd_, I2C_SLAVE, static_cast<unsigned long>(options_.address)) < 0) {
    const int code = errno;
    Close();
    return Fail(
        "not an I2C bus, or the address is taken (" + std::string(std::strerror(code)) + ")",
        error);
  }
  prescale_ = pca9685::PreScale(options_.oscillator_hz, options_.pwm_hz);
  for (const pca9685::RegisterWrite& step : pca9685::InitSequence(prescale_)) {
    const std::uint8_t bytes[2] = {step.reg, step.value};
    if (!WriteBytes(bytes, 2, error)) {
      Close();
      return false;
    }
    if (step.wait_after_us > 0) {
      std::this_thread::sleep_for(std::chrono::microseconds(step.wait_after_us));
    }
  }
  std::uint8_t readback = 0;
  if (!ReadRegister(pca9685::kPreScale, &readback, error)) {
    Close();
    return false;
  }
  if (readback != prescale_) {
    Close();
    return Fail("PRE_SCALE reads back " + std::to_string(readback) + ", wrote " +
                    std::to_string(prescale_) + " (not a PCA9685?)",
                error);
  }
  spdlog::info("servo: {} open, {:.2f} Hz", Describe(),
               pca9685::FrequencyHz(options_.oscillator_hz, prescale_));
  return true;
}

bool Pca9685ServoDriver::SetAngle(ServoAxis axis, double deg, std::string* error) {
  if (!std::isfinite(deg)) {
    return Fail(std::string(ToString(axis)) + " angle is not finite; not sent", error);
  }
  const ServoChannelMapping& mapping = axis == ServoAxis::kPan ? options_.pan : options_.tilt;
  const int ticks = pca9685::PulseTicks(mapping.PulseUs(deg), options_.oscillator_hz, prescale_);
  const auto bytes = pca9685::ChannelPulseWrite(mapping.channel, ticks);
  return WriteBytes(bytes.data(), bytes.size(), error);
}

bool Pca9685ServoDriver::ReadAngle(ServoAxis axis, double* deg, std::string* error) {
  const ServoChannelMapping& mapping = axis == ServoAxis::kPan ? options_.pan : options_.tilt;
  const auto base = static_cast<std::uint8_t>(pca9685::kLed0OnL + 4 * mapping.channel);
  std::uint8_t bytes[4] = {0, 0, 0, 0};  // ON_L, ON_H, OFF_L, OFF_H
  for (std::uint8_t i = 0; i < 4; ++i) {
    if (!ReadRegister(static_cast<std::uint8_t>(base + i), &bytes[i], error)) return false;
  }
  constexpr std::uint8_t kFullBit = 0x10;  // bit 4 of ON_H / OFF_H: fully on / fully off
  if ((bytes[1] & kFullBit) || (bytes[3] & kFullBit)) {
    return Fail("channel " + std::to_string(mapping.channel) + " is fully on or off", error);
  }
  const int on = bytes[0] | ((bytes[1] & 0x0F) << 8);
  const int off = bytes[2] | ((bytes[3] & 0x0F) << 8);
  const int ticks = (off - on + pca9685::kTicksPerPeriod) % pca9685::kTicksPerPeriod;
  if (ticks == 0) return Fail("channel " + std::to_string(mapping.channel) + " is off", error);
  const double pulse_us = pca9685::TicksPulseUs(ticks, options_.oscillator_hz, prescale_);
  *deg = (pulse_us - mapping.center_us) / mapping.us_per_deg;
  return true;
}

bool Pca9685ServoDriver::Park(std::string* error) {
  return SetAngle(ServoAxis::kPan, 0.0, error) && SetAngle(ServoAxis::kTilt, 0.0, error);
}

std::string Pca9685ServoDriver::Describe() const {
  return "pca9685 " + options_.device + " @" + Hex(options_.address) + " (pan ch " +
         std::to_string(options_.pan.channel) + ", tilt ch " +
         std::to_string(options_.tilt.channel) + ")";
}

}  // namespace kapfix::agent
