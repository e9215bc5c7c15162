#include "agent/downlink/device_health_message.hpp"

namespace kapfix::agent {
namespace {

kapfix::v1::DeviceStatus ToProto(DeviceStatus status) {
  switch (status) {
    case DeviceStatus::kOk:
      return kapfix::v1::DEVICE_OK;
    case DeviceStatus::kWaiting:
      return kapfix::v1::DEVICE_WAITING;
    case DeviceStatus::kLost:
      return kapfix::v1::DEVICE_LOST;
  }
  return kapfix::v1::DEVICE_STATUS_UNSPECIFIED;
}

}  // namespace

kapfix::v1::DeviceHealth ToProto(const DeviceHealth& health) {
  kapfix::v1::DeviceHealth message;
  message.set_status(ToProto(health.status));
  // Already bounded and valid UTF-8 (DeviceHealth's factories); bounded again here because
  // a message with an invalid string does not serialise.
  message.set_reason(BoundedUtf8(health.reason, kMaxDeviceReasonBytes));
  return message;
}

}  // namespace kapfix::agent
