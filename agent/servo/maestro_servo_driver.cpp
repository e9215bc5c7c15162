#include "agent/servo/maestro_servo_driver.hpp"

#include <fcntl.h>
#include <poll.h>
#include <spdlog/spdlog.h>
#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstring>

#include "agent/servo/libusb_maestro_usb_port.hpp"
#include "agent/servo/maestro_protocol.hpp"

namespace kapfix::agent {
namespace {

bool BaudConstant(int baud, speed_t* speed) {
  switch (baud) {
    case 9600:
      *speed = B9600;
      return true;
    case 19200:
      *speed = B19200;
      return true;
    case 38400:
      *speed = B38400;
      return true;
    case 57600:
      *speed = B57600;
      return true;
    case 115200:
      *speed = B115200;
      return true;
    default:
      return false;
  }
}

std::string ErrnoText(int code) { return std::strerror(code); }

}  // namespace

bool MaestroServoDriverOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (device.empty()) return fail("Maestro device path is empty");
  speed_t speed{};
  if (!BaudConstant(baud, &speed)) {
    return fail("Maestro baud must be 9600, 19200, 38400, 57600 or 115200, got " +
                std::to_string(baud));
  }
  std::string reason;
  if (!pan.IsValid(maestro::kMaxChannels, &reason)) return fail("Maestro pan: " + reason);
  if (!tilt.IsValid(maestro::kMaxChannels, &reason)) return fail("Maestro tilt: " + reason);
  if (pan.channel == tilt.channel) return fail("Maestro pan and tilt use the same channel");
  if (answer_timeout_ms < 1 || answer_timeout_ms > 10000) {
    return fail("Maestro answer_timeout_ms must be 1…10000, got " +
                std::to_string(answer_timeout_ms));
  }
  if (serial_timeout_ms < 10 || serial_timeout_ms > 60000 || serial_timeout_ms % 10 != 0) {
    return fail("Maestro serial_timeout_ms must be 10…60000 in 10 ms steps, got " +
                std::to_string(serial_timeout_ms));
  }
  if (!std::isfinite(pan_home_deg) || !std::isfinite(tilt_home_deg)) {
    return fail("Maestro home angles must be finite");
  }
  if (!(pan_max_rate_deg_per_s >= 0) || !(tilt_max_rate_deg_per_s >= 0) ||
      !std::isfinite(pan_max_rate_deg_per_s) || !std::isfinite(tilt_max_rate_deg_per_s)) {
    return fail("Maestro rate limits must be finite and ≥ 0 deg/s");
  }
  if (acceleration_ramp_ms < 1 || acceleration_ramp_ms > 10000) {
    return fail("Maestro acceleration_ramp_ms must be 1…10000, got " +
                std::to_string(acceleration_ramp_ms));
  }
  if (write_timeout_ms < 1 || write_timeout_ms > 10000) {
    return fail("Maestro write_timeout_ms must be 1…10000, got " +
                std::to_string(write_timeout_ms));
  }
  return true;
}

MaestroUsbSettings MaestroServoDriverOptions::UsbSettings() const {
  MaestroUsbSettings settings;
  settings.serial_timeout_ms = serial_timeout_ms;
  settings.homes = {
      {.channel = pan.channel,
       .home_quarter_us = maestro::QuarterMicroseconds(pan.PulseUs(pan_home_deg))},
      {.channel = tilt.channel,
       .home_quarter_us = maestro::QuarterMicroseconds(tilt.PulseUs(tilt_home_deg))},
  };
  return settings;
}

MaestroServoDriver::MaestroServoDriver(MaestroServoDriverOptions options,
                                       std::unique_ptr<MaestroUsbPort> usb)
    : options_(std::move(options)), usb_(std::move(usb)) {
  if (!usb_) usb_ = std::make_unique<LibusbMaestroUsbPort>(options_.device);
}

MaestroServoDriver::~MaestroServoDriver() { Close(); }

void MaestroServoDriver::Close() {
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
}

bool MaestroServoDriver::Fail(const std::string& reason, std::string* error) const {
  if (error) *error = "Maestro on " + options_.device + ": " + reason;
  return false;
}

bool MaestroServoDriver::Open(std::string* error) {
  Close();
  std::string reason;
  if (!options_.IsValid(&reason)) return Fail(reason, error);
  // Over USB first: a factory-fresh Maestro answers nothing on the Command Port until its
  // serial mode is USB Dual Port.
  usb_setup_ = ApplyMaestroUsbSettings(*usb_, options_.UsbSettings());
  fd_ = ::open(options_.device.c_str(), O_RDWR | O_NOCTTY | O_CLOEXEC | O_NONBLOCK);
  if (fd_ < 0) {
    const int code = errno;
    std::string text = "cannot open (" + ErrnoText(code) + ")";
    if (code == EACCES) text += "; is the agent's user in group dialout?";
    return Fail(text, error);
  }
  termios tty{};
  if (::tcgetattr(fd_, &tty) != 0) {
    const int code = errno;
    Close();
    return Fail("not a serial port (" + ErrnoText(code) + ")", error);
  }
  // Raw 8N1, no flow control, no echo, no line editing: every byte goes through unchanged.
  ::cfmakeraw(&tty);
  tty.c_cflag |= CLOCAL | CREAD;
  tty.c_cflag &= ~static_cast<tcflag_t>(CSTOPB | CRTSCTS);
  tty.c_cc[VMIN] = 0;
  tty.c_cc[VTIME] = 0;
  speed_t speed{};
  BaudConstant(options_.baud, &speed);
  ::cfsetispeed(&tty, speed);
  ::cfsetospeed(&tty, speed);
  if (::tcsetattr(fd_, TCSANOW, &tty) != 0) {
    const int code = errno;
    Close();
    return Fail("cannot configure the port (" + ErrnoText(code) + ")", error);
  }
  ::tcflush(fd_, TCIOFLUSH);  // stale bytes would be read as the answer below

  std::uint16_t errors = 0;
  if (!GetErrors(&errors, error)) {
    if (!usb_setup_.ok && error) *error += " (over USB: " + usb_setup_.message + ")";
    Close();
    return false;
  }
  if (errors & maestro::kErrorSerialTimeout) {
    spdlog::info(
        "Maestro on {}: serial timeout fired since the last run (the timeout is "
        "enabled); cleared",
        options_.device);
  }
  if (errors & ~maestro::kErrorSerialTimeout) {
    spdlog::warn("Maestro on {}: error register at open: {}; cleared", options_.device,
                 maestro::DescribeErrors(errors));
  }
  if (usb_setup_.ok) {
    spdlog::info("{}", usb_setup_.message);
  } else {
    spdlog::warn("{}", usb_setup_.message);
  }
  if (!CheckChannelRanges(error) || !SetSpeedAndAcceleration(error)) {
    Close();
    return false;
  }
  spdlog::info("servo: {} open", Describe());
  return true;
}

bool MaestroServoDriver::CheckChannelRanges(std::string* error) const {
  for (const MaestroChannelRange& range : usb_setup_.ranges) {
    for (const auto& [name, mapping] :
         {std::pair{"pan", &options_.pan}, std::pair{"tilt", &options_.tilt}}) {
      if (mapping->channel != range.channel) continue;
      if (mapping->min_us >= range.min_us && mapping->max_us <= range.max_us) continue;
      // The Maestro's Min/Max are in 16 µs steps: round outwards.
      const int need_min = static_cast<int>(std::floor(mapping->min_us / 16.0)) * 16;
      const int need_max = static_cast<int>(std::ceil(mapping->max_us / 16.0)) * 16;
      return Fail(fmt::format("channel {} ({}) has its own Min/Max {:g}…{:g} µs, which would "
                              "clip the mapping's {:g}…{:g} µs; set Min ≤ {} µs and Max ≥ {} "
                              "µs in Pololu's Maestro Control Center (Channel Settings), or "
                              "narrow servo.{}.min_us/max_us",
                              range.channel, name, range.min_us, range.max_us, mapping->min_us,
                              mapping->max_us, need_min, need_max, name),
                  error);
    }
  }
  return true;
}

bool MaestroServoDriver::SetSpeedAndAcceleration(std::string* error) {
  for (const auto& [mapping, rate] :
       {std::pair{&options_.pan, options_.pan_max_rate_deg_per_s},
        std::pair{&options_.tilt, options_.tilt_max_rate_deg_per_s}}) {
    if (rate <= 0) continue;
    const int speed = maestro::SpeedForRate(rate, mapping->us_per_deg);
    // Acceleration is in speed units per 80 ms: full speed after acceleration_ramp_ms.
    const int acceleration = std::clamp(
        static_cast<int>(std::ceil(speed * 80.0 / options_.acceleration_ramp_ms)), 1, 255);
    const auto set_speed = maestro::SetSpeedCommand(mapping->channel, speed);
    const auto set_acceleration = maestro::SetAccelerationCommand(mapping->channel, acceleration);
    if (!Write(set_speed.data(), set_speed.size(), error) ||
        !Write(set_acceleration.data(), set_acceleration.size(), error)) {
      return false;
    }
    spdlog::info(
        "Maestro on {}: channel {} speed limit {} (¼ µs/10 ms, {:g} deg/s), "
        "acceleration {}",
        options_.device, mapping->channel, speed, rate, acceleration);
  }
  return true;
}

bool MaestroServoDriver::Write(const std::uint8_t* bytes, std::size_t count, std::string* error) {
  if (fd_ < 0) return Fail("not open", error);
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(options_.write_timeout_ms);
  while (count > 0) {
    const ssize_t written = ::write(fd_, bytes, count);
    if (written >= 0) {
      bytes += written;
      count -= static_cast<std::size_t>(written);
      continue;
    }
    if (errno == EINTR) continue;
    if (errno != EAGAIN && errno != EWOULDBLOCK) {
      return Fail("write failed (" + ErrnoText(errno) + "); Maestro unplugged?", error);
    }
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    pollfd p{fd_, POLLOUT, 0};
    const int ready = left.count() > 0 ? ::poll(&p, 1, static_cast<int>(left.count())) : 0;
    if (ready < 0 && errno == EINTR) continue;
    if (ready == 0) {
      return Fail("port did not take a command within " +
                      std::to_string(options_.write_timeout_ms) + " ms (wedged?)",
                  error);
    }
    if (ready < 0 || (p.revents & (POLLERR | POLLHUP | POLLNVAL))) {
      return Fail("port failed while writing; Maestro unplugged?", error);
    }
  }
  return true;
}

bool MaestroServoDriver::ReadAnswer(std::uint8_t* answer, std::size_t count,
                                    const std::string& what, std::string* error) {
  std::size_t received = 0;
  const auto deadline =
      std::chrono::steady_clock::now() + std::chrono::milliseconds(options_.answer_timeout_ms);
  while (received < count) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
        deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) break;
    pollfd p{fd_, POLLIN, 0};
    const int ready = ::poll(&p, 1, static_cast<int>(left.count()));
    if (ready < 0 && errno == EINTR) continue;
    if (ready <= 0) break;
    const ssize_t got = ::read(fd_, answer + received, count - received);
    if (got < 0 && (errno == EINTR || errno == EAGAIN)) continue;
    if (got <= 0) break;
    received += static_cast<std::size_t>(got);
  }
  if (received < count) {
    return Fail("no answer to " + what + " within " + std::to_string(options_.answer_timeout_ms) +
                    " ms; is its serial mode \"USB Dual Port\" (use the Command Port) or a fixed "
                    "baud rate of " +
                    std::to_string(options_.baud) + "?",
                error);
  }
  return true;
}

bool MaestroServoDriver::GetErrors(std::uint16_t* errors, std::string* error) {
  const std::uint8_t command = maestro::kGetErrors;
  if (!Write(&command, 1, error)) return false;
  std::uint8_t answer[2] = {0, 0};
  if (!ReadAnswer(answer, 2, "Get Errors (0xA1)", error)) return false;
  *errors = maestro::ErrorRegister(answer[0], answer[1]);
  return true;
}

bool MaestroServoDriver::ReadAngle(ServoAxis axis, double* deg, std::string* error) {
  const ServoChannelMapping& mapping = axis == ServoAxis::kPan ? options_.pan : options_.tilt;
  if (fd_ < 0) return Fail("not open", error);
  ::tcflush(fd_, TCIFLUSH);
  const std::uint8_t command[2] = {maestro::kGetPosition,
                                   static_cast<std::uint8_t>(mapping.channel & 0x7F)};
  if (!Write(command, 2, error)) return false;
  std::uint8_t answer[2] = {0, 0};
  if (!ReadAnswer(answer, 2, "Get Position (0x90)", error)) return false;
  const int quarter_us = answer[0] | (answer[1] << 8);
  if (quarter_us == 0) return Fail("channel " + std::to_string(mapping.channel) + " is off", error);
  *deg = (quarter_us / 4.0 - mapping.center_us) / mapping.us_per_deg;
  return true;
}

bool MaestroServoDriver::SetAngle(ServoAxis axis, double deg, std::string* error) {
  if (!std::isfinite(deg)) {
    return Fail(std::string(ToString(axis)) + " angle is not finite; not sent", error);
  }
  const ServoChannelMapping& mapping = axis == ServoAxis::kPan ? options_.pan : options_.tilt;
  const auto command = maestro::SetTargetCommand(
      mapping.channel, maestro::QuarterMicroseconds(mapping.PulseUs(deg)));
  return Write(command.data(), command.size(), error);
}

bool MaestroServoDriver::Park(std::string* error) {
  return SetAngle(ServoAxis::kPan, 0.0, error) && SetAngle(ServoAxis::kTilt, 0.0, error);
}

std::string MaestroServoDriver::Describe() const {
  return "maestro " + options_.device + " (pan ch " + std::to_string(options_.pan.channel) +
         ", tilt ch " + std::to_string(options_.tilt.channel) + ")";
}

}  // namespace kapfix::agent
