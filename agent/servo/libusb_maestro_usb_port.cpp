#include "agent/servo/libusb_maestro_usb_port.hpp"

#include <libusb.h>
#include <limits.h>
#include <stdlib.h>

#include <fstream>
#include <string>
#include <vector>

namespace kapfix::agent {
namespace {

constexpr unsigned kTransferTimeoutMs = 1000;  // [ms] a parameter write stores to EEPROM

// What to do when the Maestro's USB node cannot be opened for lack of permission.
constexpr const char* kUdevAdvice =
    "the udev rule 99-kapfix-maestro.rules gives group plugdev (the agent's user is in it) "
    "access: the kapfix-agent package installs it in /lib/udev/rules.d, from a source build "
    "copy deploy/udev/99-kapfix-maestro.rules to /etc/udev/rules.d; then run `udevadm control "
    "--reload && udevadm trigger` or replug the Maestro";

std::string ProductName(std::uint16_t product_id) {
  switch (product_id) {
    case maestro::kProductMicro6:
      return "Micro Maestro 6";
    case maestro::kProductMini12:
      return "Mini Maestro 12";
    case maestro::kProductMini18:
      return "Mini Maestro 18";
    case maestro::kProductMini24:
      return "Mini Maestro 24";
    default:
      return "Maestro";
  }
}

std::string RealPath(const std::string& path) {
  char resolved[PATH_MAX];
  if (::realpath(path.c_str(), resolved) == nullptr) return "";
  return resolved;
}

int ReadNumber(const std::string& path) {
  std::ifstream file(path);
  int value = -1;
  if (!(file >> value)) return -1;
  return value;
}

// The USB bus and address of the device that owns the tty `device` (sysfs: the tty's
// "device" is a USB interface whose parent directory is the USB device, with busnum and
// devnum). False for ttys that are not on USB (UARTs) and for paths that are not ttys.
bool UsbLocationOfTty(const std::string& device, int* bus, int* address) {
  const std::string tty = RealPath(device);
  const std::size_t slash = tty.rfind('/');
  if (tty.empty() || slash == std::string::npos) return false;
  std::string dir = RealPath("/sys/class/tty/" + tty.substr(slash + 1) + "/device");
  for (int level = 0; level < 3 && !dir.empty(); ++level) {
    const int b = ReadNumber(dir + "/busnum");
    const int a = ReadNumber(dir + "/devnum");
    if (b >= 0 && a >= 0) {
      *bus = b;
      *address = a;
      return true;
    }
    const std::size_t up = dir.rfind('/');
    dir = up == std::string::npos ? "" : dir.substr(0, up);
  }
  return false;
}

std::string UsbError(int code) {
  return std::string(libusb_error_name(code)) + ": " + libusb_strerror(code);
}

}  // namespace

LibusbMaestroUsbPort::LibusbMaestroUsbPort(std::string serial_device)
    : serial_device_(std::move(serial_device)) {}

LibusbMaestroUsbPort::~LibusbMaestroUsbPort() { Close(); }

void LibusbMaestroUsbPort::Close() {
  if (handle_) libusb_close(handle_);
  handle_ = nullptr;
  if (context_) libusb_exit(context_);
  context_ = nullptr;
}

bool LibusbMaestroUsbPort::Open(std::string* error) {
  Close();
  auto fail = [this, error](const std::string& reason) {
    Close();
    if (error) *error = reason;
    return false;
  };
  const int init = libusb_init(&context_);
  if (init != 0) {
    context_ = nullptr;
    return fail("libusb cannot start (" + UsbError(init) + ")");
  }
  int tty_bus = -1;
  int tty_address = -1;
  const bool tty_on_usb = UsbLocationOfTty(serial_device_, &tty_bus, &tty_address);

  libusb_device** list = nullptr;
  const ssize_t count = libusb_get_device_list(context_, &list);
  if (count < 0) return fail("cannot list USB devices (" + UsbError(static_cast<int>(count)) + ")");
  std::vector<libusb_device*> maestros;
  libusb_device* chosen = nullptr;
  for (ssize_t i = 0; i < count; ++i) {
    libusb_device_descriptor descriptor{};
    if (libusb_get_device_descriptor(list[i], &descriptor) != 0) continue;
    if (descriptor.idVendor != maestro::kUsbVendorId ||
        maestro::ChannelCount(descriptor.idProduct) == 0) {
      continue;
    }
    maestros.push_back(list[i]);
    if (tty_on_usb && libusb_get_bus_number(list[i]) == tty_bus &&
        libusb_get_device_address(list[i]) == tty_address) {
      chosen = list[i];
    }
  }
  std::string not_found;
  if (!chosen && maestros.size() == 1) {
    chosen = maestros.front();  // e.g. wired to a UART and also plugged in to USB
  } else if (!chosen && maestros.empty()) {
    not_found = "no Maestro found on USB (vendor 1ffb, product 0089/008a/008b/008c)";
    if (!tty_on_usb) {
      not_found += "; " + serial_device_ +
                   " is not a USB port, so this Maestro is on TTL serial only: plug its USB "
                   "into the computer too";
    }
  } else if (!chosen) {
    not_found = std::to_string(maestros.size()) + " Maestros on USB and none of them owns " +
                serial_device_ + "; cannot tell which one to set";
  }
  if (chosen) {
    libusb_device_descriptor descriptor{};
    libusb_get_device_descriptor(chosen, &descriptor);
    product_id_ = descriptor.idProduct;
    bus_ = libusb_get_bus_number(chosen);
    address_ = libusb_get_device_address(chosen);
    const int opened = libusb_open(chosen, &handle_);
    if (opened != 0) {
      handle_ = nullptr;
      libusb_free_device_list(list, 1);
      std::string reason = "cannot open " + Describe() + " (" + UsbError(opened) + ")";
      if (opened == LIBUSB_ERROR_ACCESS) reason += std::string(": no permission; ") + kUdevAdvice;
      return fail(reason);
    }
  }
  libusb_free_device_list(list, 1);
  if (!handle_) return fail(not_found);
  return true;
}

std::string LibusbMaestroUsbPort::Describe() const {
  return ProductName(product_id_) + " (USB bus " + std::to_string(bus_) + " address " +
         std::to_string(address_) + ")";
}

bool LibusbMaestroUsbPort::Transfer(const MaestroControlTransfer& transfer,
                                    std::vector<std::uint8_t>* in, std::string* error) {
  if (!handle_) {
    if (error) *error = "not open";
    return false;
  }
  const bool reads = (transfer.request_type & LIBUSB_ENDPOINT_IN) != 0;
  std::vector<std::uint8_t> buffer(reads ? transfer.length : 0);
  const int done = libusb_control_transfer(
      handle_, transfer.request_type, transfer.request, transfer.value, transfer.index,
      buffer.data(), static_cast<std::uint16_t>(buffer.size()), kTransferTimeoutMs);
  if (done < 0) {
    if (error) {
      *error = UsbError(done);
      if (done == LIBUSB_ERROR_ACCESS) *error += "; " + std::string(kUdevAdvice);
    }
    return false;
  }
  if (reads) {
    if (static_cast<std::size_t>(done) != buffer.size()) {
      if (error) {
        *error = "short read: " + std::to_string(done) + " of " + std::to_string(buffer.size()) +
                 " bytes";
      }
      return false;
    }
    if (in) *in = std::move(buffer);
  }
  return true;
}

}  // namespace kapfix::agent
