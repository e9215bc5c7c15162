#pragma once

#include <cstdint>
#include <string>
#include <vector>

// The parts of the Pololu Maestro's native USB interface that the agent uses: vendor control
// transfers on endpoint 0 that read and write its persistent parameters (Pololu USB SDK,
// Maestro/Usc/Usc.cs and Usc_protocol.cs). The serial Command Port cannot reach these, so the
// serial timeout and the channels' "On startup or error" positions are set this way.
namespace kapfix::agent::maestro {

inline constexpr std::uint16_t kUsbVendorId = 0x1FFB;  // Pololu
inline constexpr std::uint16_t kProductMicro6 = 0x0089;
inline constexpr std::uint16_t kProductMini12 = 0x008A;
inline constexpr std::uint16_t kProductMini18 = 0x008B;
inline constexpr std::uint16_t kProductMini24 = 0x008C;

// Channels of a Maestro by USB product id; 0 for ids that are not a Maestro.
int ChannelCount(std::uint16_t product_id);

// bmRequestType: vendor request to the device, host to device (OUT) or device to host (IN).
inline constexpr std::uint8_t kRequestTypeOut = 0x40;
inline constexpr std::uint8_t kRequestTypeIn = 0xC0;
// bRequest values.
inline constexpr std::uint8_t kRequestGetParameter = 0x81;  // wIndex = parameter; reads 1 or 2 B
inline constexpr std::uint8_t kRequestSetParameter = 0x82;  // wValue = value,
                                                            // wIndex = size << 8 | parameter
inline constexpr std::uint8_t kRequestReinitialize = 0x90;  // re-reads the parameters

// Parameter numbers. The same on the Micro and the Mini Maestros; each channel has 9 bytes of
// parameters from kParameterServo0Home on (9 · 24 channels fit below 256).
inline constexpr std::uint8_t kParameterSerialMode = 3;    // 1 B, kSerialMode*
inline constexpr std::uint8_t kSerialModeUsbDualPort = 0;  // Command Port takes commands
inline constexpr std::uint8_t kSerialModeUsbChained = 1;
inline constexpr std::uint8_t kSerialModeUartDetectBaud = 2;  // the factory setting
inline constexpr std::uint8_t kSerialModeUartFixedBaud = 3;
inline constexpr std::uint8_t kParameterSerialTimeout = 6;  // 2 B [10 ms], 0 = off
inline constexpr std::uint8_t kParameterServo0Home = 30;    // 2 B [quarter-µs], 0 = off,
                                                            // 1 = ignore
inline constexpr std::uint8_t kParameterServo0Min = 32;     // 1 B [64 quarter-µs] lowest target
inline constexpr std::uint8_t kParameterServo0Max = 33;     // 1 B [64 quarter-µs] highest target
inline constexpr std::uint8_t kServoParameterBytes = 9;
inline constexpr int kMaxHome = 32440;              // [quarter-µs] largest home value
inline constexpr int kMaxSerialTimeoutMs = 655350;  // 0xFFFF · 10 ms

}  // namespace kapfix::agent::maestro

namespace kapfix::agent {

// One USB control transfer on endpoint 0. OUT transfers here carry no data; IN transfers
// read `length` bytes.
struct MaestroControlTransfer {
  std::uint8_t request_type = 0;
  std::uint8_t request = 0;
  std::uint16_t value = 0;
  std::uint16_t index = 0;
  std::uint16_t length = 0;

  bool operator==(const MaestroControlTransfer&) const = default;
};

// One Maestro parameter with the value the agent wants in it.
struct MaestroParameter {
  std::uint8_t id = 0;
  std::uint8_t size = 0;  // [B] 1 or 2
  std::uint16_t value = 0;
  std::string name;  // for the log: "serial timeout", "channel 0 home"

  bool operator==(const MaestroParameter&) const = default;
};

// A channel's "On startup or error" position: Go to `home_quarter_us`.
struct MaestroHome {
  int channel = 0;
  int home_quarter_us = 6000;  // [quarter-µs] 6000 = 1500 µs
};

// What the agent sets on the Maestro.
struct MaestroUsbSettings {
  int serial_timeout_ms = 500;  // [ms] rounded to the Maestro's 10 ms steps
  std::vector<MaestroHome> homes;

  // 10 ≤ serial_timeout_ms ≤ 655350, channels 0…23, each channel once,
  // 2 ≤ home_quarter_us ≤ 32440 (0 and 1 would mean Off and Ignore).
  bool IsValid(std::string* error) const;
};

// Serial mode "USB Dual Port": without it the Command Port ignores the agent (a factory-fresh
// Maestro is in "UART, detect baud rate").
MaestroParameter SerialModeParameter();

// A channel's own target range (its Min and Max in the Control Center) [µs]: the Maestro
// clamps every target into it, whatever the agent sends. Factory: 992…2000 µs.
struct MaestroChannelRange {
  int channel = 0;
  double min_us = 0;
  double max_us = 0;
};
// The two 1-byte parameters (kParameterServo0Min/Max + 9 · channel) to read; value · 16 µs.
MaestroParameter ChannelMinParameter(int channel);
MaestroParameter ChannelMaxParameter(int channel);

// The wanted parameters: the serial timeout first, then each channel's home, in the order
// given. Values are clamped to what the parameters can hold; call IsValid first.
std::vector<MaestroParameter> MaestroSettingsParameters(const MaestroUsbSettings& settings);

// REQUEST_SET_PARAMETER for `parameter`: 40 82, wValue = value, wIndex = size << 8 | id.
MaestroControlTransfer SetParameterTransfer(const MaestroParameter& parameter);
// REQUEST_GET_PARAMETER for `parameter`: C0 81, wValue = 0, wIndex = id, reads `size` bytes.
MaestroControlTransfer GetParameterTransfer(const MaestroParameter& parameter);
// REQUEST_REINITIALIZE: 40 90 0 0. Makes the written parameters take effect (Pololu's tools
// send it after writing settings) and sends the channels to their home positions.
MaestroControlTransfer ReinitializeTransfer();

// Writes of every parameter in order, then one reinitialize; nothing for an empty list.
std::vector<MaestroControlTransfer> MaestroSettingsTransfers(
    const std::vector<MaestroParameter>& parameters);
std::vector<MaestroControlTransfer> MaestroSettingsTransfers(const MaestroUsbSettings& settings);

// A parameter's value from the bytes GET_PARAMETER returned (little-endian).
std::uint16_t ParameterValue(const std::vector<std::uint8_t>& bytes);

// "500 ms (50)" for the serial timeout, "1500 µs (6000)" for a home, "off (0)", "ignore (1)".
std::string DescribeParameterValue(const MaestroParameter& parameter, std::uint16_t value);

}  // namespace kapfix::agent
