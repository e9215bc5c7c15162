#include "agent/servo/maestro_usb_settings.hpp"

#include <algorithm>
#include <set>

#include "agent/servo/maestro_protocol.hpp"

namespace kapfix::agent {
namespace maestro {

int ChannelCount(std::uint16_t product_id) {
  switch (product_id) {
    case kProductMicro6:
      return 6;
    case kProductMini12:
      return 12;
    case kProductMini18:
      return 18;
    case kProductMini24:
      return 24;
    default:
      return 0;
  }
}

}  // namespace maestro

namespace {

// Home values 0 and 1 are the modes Off and Ignore, not positions.
constexpr int kMinHome = 2;
constexpr int kTimeoutStepMs = 10;

}  // namespace

bool MaestroUsbSettings::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (serial_timeout_ms < kTimeoutStepMs || serial_timeout_ms > maestro::kMaxSerialTimeoutMs) {
    return fail("serial timeout must be 10…655350 ms, got " + std::to_string(serial_timeout_ms));
  }
  std::set<int> channels;
  for (const MaestroHome& home : homes) {
    if (home.channel < 0 || home.channel >= maestro::kMaxChannels) {
      return fail("channel must be 0…23, got " + std::to_string(home.channel));
    }
    if (!channels.insert(home.channel).second) {
      return fail("channel " + std::to_string(home.channel) + " is given twice");
    }
    if (home.home_quarter_us < kMinHome || home.home_quarter_us > maestro::kMaxHome) {
      return fail("channel " + std::to_string(home.channel) +
                  " home must be 2…32440 quarter-µs, got " + std::to_string(home.home_quarter_us));
    }
  }
  return true;
}

std::vector<MaestroParameter> MaestroSettingsParameters(const MaestroUsbSettings& settings) {
  std::vector<MaestroParameter> parameters;
  const int steps = std::clamp((settings.serial_timeout_ms + kTimeoutStepMs / 2) / kTimeoutStepMs,
                               1, int{0xFFFF});
  parameters.push_back({.id = maestro::kParameterSerialTimeout,
                        .size = 2,
                        .value = static_cast<std::uint16_t>(steps),
                        .name = "serial timeout"});
  for (const MaestroHome& home : settings.homes) {
    const int channel = std::clamp(home.channel, 0, maestro::kMaxChannels - 1);
    const int id = maestro::kParameterServo0Home + channel * maestro::kServoParameterBytes;
    parameters.push_back({.id = static_cast<std::uint8_t>(id),
                          .size = 2,
                          .value = static_cast<std::uint16_t>(
                              std::clamp(home.home_quarter_us, kMinHome, maestro::kMaxHome)),
                          .name = "channel " + std::to_string(channel) + " home"});
  }
  return parameters;
}

MaestroParameter SerialModeParameter() {
  return {.id = maestro::kParameterSerialMode,
          .size = 1,
          .value = maestro::kSerialModeUsbDualPort,
          .name = "serial mode"};
}

MaestroParameter ChannelMinParameter(int channel) {
  const int c = std::clamp(channel, 0, maestro::kMaxChannels - 1);
  return {.id = static_cast<std::uint8_t>(maestro::kParameterServo0Min +
                                          c * maestro::kServoParameterBytes),
          .size = 1,
          .value = 0,
          .name = "channel " + std::to_string(c) + " min"};
}

MaestroParameter ChannelMaxParameter(int channel) {
  const int c = std::clamp(channel, 0, maestro::kMaxChannels - 1);
  return {.id = static_cast<std::uint8_t>(maestro::kParameterServo0Max +
                                          c * maestro::kServoParameterBytes),
          .size = 1,
          .value = 0,
          .name = "channel " + std::to_string(c) + " max"};
}

MaestroControlTransfer SetParameterTransfer(const MaestroParameter& parameter) {
  return {.request_type = maestro::kRequestTypeOut,
          .request = maestro::kRequestSetParameter,
          .value = parameter.value,
          .index = static_cast<std::uint16_t>((parameter.size << 8) | parameter.id),
          .length = 0};
}

MaestroControlTransfer GetParameterTransfer(const MaestroParameter& parameter) {
  return {.request_type = maestro::kRequestTypeIn,
          .request = maestro::kRequestGetParameter,
          .value = 0,
          .index = parameter.id,
          .length = parameter.size};
}

MaestroControlTransfer ReinitializeTransfer() {
  return {.request_type = maestro::kRequestTypeOut,
          .request = maestro::kRequestReinitialize,
          .value = 0,
          .index = 0,
          .length = 0};
}

std::vector<MaestroControlTransfer> MaestroSettingsTransfers(
    const std::vector<MaestroParameter>& parameters) {
  std::vector<MaestroControlTransfer> transfers;
  if (parameters.empty()) return transfers;
  for (const MaestroParameter& parameter : parameters) {
    transfers.push_back(SetParameterTransfer(parameter));
  }
  transfers.push_back(ReinitializeTransfer());
  return transfers;
}

std::vector<MaestroControlTransfer> MaestroSettingsTransfers(const MaestroUsbSettings& settings) {
  return MaestroSettingsTransfers(MaestroSettingsParameters(settings));
}

std::uint16_t ParameterValue(const std::vector<std::uint8_t>& bytes) {
  std::uint16_t value = 0;
  if (!bytes.empty()) value = bytes[0];
  if (bytes.size() > 1) value = static_cast<std::uint16_t>(value | (bytes[1] << 8));
  return value;
}

std::string DescribeParameterValue(const MaestroParameter& parameter, std::uint16_t value) {
  const std::string raw = " (" + std::to_string(value) + ")";
  if (parameter.id == maestro::kParameterSerialTimeout) {
    if (value == 0) return "off" + raw;
    return std::to_string(value * kTimeoutStepMs) + " ms" + raw;
  }
  if (parameter.id == maestro::kParameterSerialMode) {
    switch (value) {
      case maestro::kSerialModeUsbDualPort:
        return "USB Dual Port" + raw;
      case maestro::kSerialModeUsbChained:
        return "USB Chained" + raw;
      case maestro::kSerialModeUartDetectBaud:
        return "UART, detect baud rate" + raw;
      case maestro::kSerialModeUartFixedBaud:
        return "UART, fixed baud rate" + raw;
      default:
        return "unknown" + raw;
    }
  }
  if (value == 0) return "off" + raw;
  if (value == 1) return "ignore" + raw;
  // [quarter-µs] → µs with the quarter shown only when there is one.
  std::string us = std::to_string(value / 4);
  if (value % 4 != 0) us += "." + std::to_string(value % 4 * 25);
  return us + " µs" + raw;
}

}  // namespace kapfix::agent
