#pragma once

#include <string>
#include <vector>

#include "agent/servo/maestro_usb_port.hpp"
#include "agent/servo/maestro_usb_settings.hpp"

namespace kapfix::agent {

// What ApplyMaestroUsbSettings did, as one log line.
struct MaestroUsbSetupResult {
  bool ok = false;       // every parameter holds its wanted value, read back from the Maestro
  bool changed = false;  // something was written (and the Maestro reinitialized)
  std::string message;   // ok: what was set; not ok: the cause, the risk and what to do
  // Each home channel's own Min/Max, read in the same session (empty if it failed before).
  std::vector<MaestroChannelRange> ranges;
};

// Sets the Maestro's serial mode (USB Dual Port, so that a factory-fresh Maestro takes
// commands on its Command Port), its serial timeout and the channels' "On startup or error" home
// positions through `port`: opens it, reads every wanted parameter, writes only those that differ
// (they are stored in the Maestro's EEPROM; rewriting equal values each start would wear it for
// nothing), reinitializes the Maestro if anything was written (that is when written values
// take effect; the channels go to their home positions then, which is park), reads every
// parameter back and compares. Closes the port before returning.
MaestroUsbSetupResult ApplyMaestroUsbSettings(MaestroUsbPort& port,
                                              const MaestroUsbSettings& settings);

}  // namespace kapfix::agent
