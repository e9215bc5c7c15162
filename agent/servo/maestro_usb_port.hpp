#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "agent/servo/maestro_usb_settings.hpp"

namespace kapfix::agent {

// The seam to a Maestro's native USB interface (its vendor-specific interface, beside the two
// serial ports): find and open the Maestro, run control transfers on endpoint 0.
// LibusbMaestroUsbPort is the real one; tests use a fake.
class MaestroUsbPort {
 public:
  virtual ~MaestroUsbPort() = default;

  // Finds the Maestro and opens it. On failure the reason names the cause and what to do
  // (udev rule, no Maestro on USB, built without libusb…).
  virtual bool Open(std::string* error) = 0;
  virtual void Close() = 0;
  // USB product id of the open Maestro (maestro::kProductMicro6…kProductMini24).
  virtual std::uint16_t product_id() const = 0;
  // "Mini Maestro 12 (USB bus 1 address 5)", for the log.
  virtual std::string Describe() const = 0;
  // Runs one control transfer. IN transfers put the bytes read into `in` (exactly
  // transfer.length of them, or it fails); OUT transfers leave it alone.
  virtual bool Transfer(const MaestroControlTransfer& transfer, std::vector<std::uint8_t>* in,
                        std::string* error) = 0;
};

}  // namespace kapfix::agent
