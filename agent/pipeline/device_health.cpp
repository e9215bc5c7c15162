#include "agent/pipeline/device_health.hpp"

namespace kapfix::agent {
namespace {

// [bytes] the length of the UTF-8 sequence starting at text[at], 0 if it is not a valid one
// (overlong forms, surrogates and code points beyond U+10FFFF included).
std::size_t Utf8SequenceLength(std::string_view text, std::size_t at) {
  const auto byte = [&text](std::size_t i) { return static_cast<unsigned char>(text[i]); };
  const unsigned char lead = byte(at);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned char low = 0x80;  // the second byte's range, narrower for some leads
  unsigned char high = 0xBF;
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) low = 0xA0;
    if (lead == 0xED) high = 0x9F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) low = 0x90;
    if (lead == 0xF4) high = 0x8F;
  } else {
    return 0;
  }
  if (at + length > text.size()) return 0;
  if (byte(at + 1) < low || byte(at + 1) > high) return 0;
  for (std::size_t i = 2; i < length; ++i) {
    if (byte(at + i) < 0x80 || byte(at + i) > 0xBF) return 0;
  }
  return length;
}

}  // namespace

DeviceHealth DeviceHealth::Waiting(std::string_view reason) {
  return {DeviceStatus::kWaiting, BoundedUtf8(reason, kMaxDeviceReasonBytes)};
}

DeviceHealth DeviceHealth::Lost(std::string_view reason) {
  return {DeviceStatus::kLost, BoundedUtf8(reason, kMaxDeviceReasonBytes)};
}

DeviceHealth DeviceHealth::Reopening(const DeviceHealth& out) {
  if (out.reopening()) return out;
  return {out.status,
          BoundedUtf8(std::string(kReopeningPrefix) + out.reason, kMaxDeviceReasonBytes)};
}

bool DeviceHealth::reopening() const { return reason.rfind(kReopeningPrefix, 0) == 0; }

std::string BoundedUtf8(std::string_view text, std::size_t max_bytes) {
  std::string out;
  for (std::size_t at = 0; at < text.size();) {
    const std::size_t length = Utf8SequenceLength(text, at);
    // An invalid byte is one byte in and one '?' out.
    const std::size_t step = length == 0 ? 1 : length;
    if (out.size() + step > max_bytes) break;
    if (length == 0) {
      out += '?';
    } else {
      out.append(text.substr(at, length));
    }
    at += step;
  }
  return out;
}

std::string_view DeviceStatusWord(DeviceStatus status) {
  switch (status) {
    case DeviceStatus::kOk:
      return "ok";
    case DeviceStatus::kWaiting:
      return "waiting";
    case DeviceStatus::kLost:
      return "lost";
  }
  return "?";
}

std::string StatusLine(const DevicesHealth& health) {
  std::string line;
  for (const auto& [name, device] :
       {std::pair<std::string_view, const DeviceHealth&>{"camera", health.camera},
        std::pair<std::string_view, const DeviceHealth&>{"servos", health.servos}}) {
    if (!line.empty()) line += "; ";
    line.append(name).append(" ").append(DeviceStatusWord(device.status));
    if (!device.reason.empty()) line.append(": ").append(device.reason);
  }
  return line;
}

}  // namespace kapfix::agent
