#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "agent/servo/maestro_protocol.hpp"
#include "agent/servo/maestro_usb_port.hpp"
#include "agent/servo/maestro_usb_settings.hpp"

namespace kapfix::agent {

// A Maestro's native USB interface in memory: parameters in a map (its EEPROM), every
// transfer recorded. Knobs make it fail to open, refuse writes or drop them silently.
class FakeMaestroUsbPort : public MaestroUsbPort {
 public:
  // A Maestro as it leaves the factory: serial mode "UART, detect baud rate" (the Command
  // Port ignores commands), every channel's Min/Max 992…2000 µs (62 and 125 · 16 µs).
  static std::map<std::uint8_t, std::uint16_t> FactoryEeprom() {
    std::map<std::uint8_t, std::uint16_t> eeprom;
    eeprom[maestro::kParameterSerialMode] = maestro::kSerialModeUartDetectBaud;
    for (int channel = 0; channel < maestro::kMaxChannels; ++channel) {
      eeprom[static_cast<std::uint8_t>(ChannelMinParameter(channel).id)] = 62;
      eeprom[static_cast<std::uint8_t>(ChannelMaxParameter(channel).id)] = 125;
    }
    return eeprom;
  }

  struct State {
    std::uint16_t product_id = maestro::kProductMini12;
    std::string open_error;      // non-empty: Open fails with it
    bool refuse_writes = false;  // SET_PARAMETER fails
    bool drop_writes = false;    // SET_PARAMETER "succeeds", stores nothing
    std::map<std::uint8_t, std::uint16_t> eeprom = FactoryEeprom();  // id → value; absent = 0
    std::vector<MaestroControlTransfer> transfers;
    int opens = 0;
    bool open = false;
  };

  // `state` outlives the port, so that a test can look at it after handing the port over.
  explicit FakeMaestroUsbPort(State* state) : state_(state) {}

  bool Open(std::string* error) override {
    ++state_->opens;
    if (!state_->open_error.empty()) {
      if (error) *error = state_->open_error;
      return false;
    }
    state_->open = true;
    return true;
  }
  void Close() override { state_->open = false; }
  std::uint16_t product_id() const override { return state_->product_id; }
  std::string Describe() const override { return "fake Maestro"; }
  bool Transfer(const MaestroControlTransfer& transfer, std::vector<std::uint8_t>* in,
                std::string* error) override {
    state_->transfers.push_back(transfer);
    if (!state_->open) {
      if (error) *error = "not open";
      return false;
    }
    if (transfer.request == maestro::kRequestGetParameter) {
      const std::uint16_t value = state_->eeprom[static_cast<std::uint8_t>(transfer.index)];
      in->assign({static_cast<std::uint8_t>(value & 0xFF), static_cast<std::uint8_t>(value >> 8)});
      in->resize(transfer.length);
      return true;
    }
    if (transfer.request == maestro::kRequestSetParameter) {
      if (state_->refuse_writes) {
        if (error) *error = "LIBUSB_ERROR_PIPE: Pipe error";
        return false;
      }
      if (!state_->drop_writes) {
        state_->eeprom[static_cast<std::uint8_t>(transfer.index & 0xFF)] = transfer.value;
      }
      return true;
    }
    return transfer.request == maestro::kRequestReinitialize;
  }

 private:
  State* state_;
};

}  // namespace kapfix::agent
