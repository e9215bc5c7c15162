// LibusbMaestroUsbPort when kapfix was built without libusb-1.0 (agent/servo/CMakeLists.txt):
// every Open fails with that reason, so the agent warns and flies on with the serial port.
#include "agent/servo/libusb_maestro_usb_port.hpp"

namespace kapfix::agent {

LibusbMaestroUsbPort::LibusbMaestroUsbPort(std::string serial_device)
    : serial_device_(std::move(serial_device)) {}

LibusbMaestroUsbPort::~LibusbMaestroUsbPort() = default;

bool LibusbMaestroUsbPort::Open(std::string* error) {
  if (error) {
    *error =
        "kapfix-agent was built without libusb-1.0 (install libusb-1.0-0-dev and rebuild: "
        "deploy/setup-debian.sh)";
  }
  return false;
}

// Nothing is ever open; the fields are the real implementation's.
void LibusbMaestroUsbPort::Close() {
  context_ = nullptr;
  handle_ = nullptr;
  product_id_ = 0;
  bus_ = 0;
  address_ = 0;
}

std::string LibusbMaestroUsbPort::Describe() const { return "Maestro (no libusb)"; }

bool LibusbMaestroUsbPort::Transfer(const MaestroControlTransfer& /*transfer*/,
                                    std::vector<std::uint8_t>* /*in*/, std::string* error) {
  if (error) *error = "built without libusb-1.0";
  return false;
}

}  // namespace kapfix::agent
