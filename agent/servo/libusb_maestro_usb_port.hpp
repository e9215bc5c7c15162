#pragma once

#include <cstdint>
#include <string>

#include "agent/servo/maestro_usb_port.hpp"

struct libusb_context;
struct libusb_device_handle;

namespace kapfix::agent {

// The Maestro's native USB interface through libusb-1.0. Which Maestro: the one whose USB
// device owns `serial_device` (found through sysfs, so /dev/serial/by-id/… links work too);
// if that port is not a Maestro's (a Maestro wired to a UART), the only Maestro on USB, if
// there is exactly one. Needs write access to its /dev/bus/usb node (a udev rule:
// deploy/udev/99-kapfix-maestro.rules). Control transfers to the device need no claimed
// interface, so the kernel's cdc_acm keeps the serial ports.
// Built from libusb_maestro_usb_port_stub.cpp instead when libusb-1.0 was not found: every
// Open then fails with that reason.
class LibusbMaestroUsbPort : public MaestroUsbPort {
 public:
  explicit LibusbMaestroUsbPort(std::string serial_device);
  ~LibusbMaestroUsbPort() override;
  LibusbMaestroUsbPort(const LibusbMaestroUsbPort&) = delete;
  LibusbMaestroUsbPort& operator=(const LibusbMaestroUsbPort&) = delete;

  bool Open(std::string* error) override;
  void Close() override;
  std::uint16_t product_id() const override { return product_id_; }
  std::string Describe() const override;
  bool Transfer(const MaestroControlTransfer& transfer, std::vector<std::uint8_t>* in,
                std::string* error) override;

 private:
  std::string serial_device_;
  libusb_context* context_ = nullptr;
  libusb_device_handle* handle_ = nullptr;
  std::uint16_t product_id_ = 0;
  int bus_ = 0;
  int address_ = 0;
};

}  // namespace kapfix::agent
