#include "agent/servo/maestro_usb_setup.hpp"

#include <chrono>
#include <thread>

namespace kapfix::agent {
namespace {

// [ms] Pololu's tools wait this long after REQUEST_REINITIALIZE before talking to the Maestro.
constexpr int kReinitializeWaitMs = 50;

// The same values as the Control Center shows them: the timeout in seconds, homes in µs.
std::string ManualAdvice(const MaestroUsbSettings& settings) {
  const auto parameters = MaestroSettingsParameters(settings);
  const int centiseconds = parameters.front().value;  // [10 ms]
  std::string hundredths = std::to_string(centiseconds % 100);
  if (hundredths.size() < 2) hundredths.insert(0, "0");
  std::string text =
      "set them once in Pololu's Maestro Control Center instead: Serial Settings → Timeout = " +
      std::to_string(centiseconds / 100) + "." + hundredths + " s";
  for (std::size_t i = 1; i < parameters.size() && i <= settings.homes.size(); ++i) {
    text += "; channel " + std::to_string(settings.homes[i - 1].channel) +
            " \"On startup or error\" = Go to " +
            DescribeParameterValue(parameters[i], parameters[i].value);
  }
  return text + "; Serial Settings → Serial mode = USB Dual Port";
}

MaestroUsbSetupResult Failure(const MaestroUsbSettings& settings, const std::string& cause) {
  return {.ok = false,
          .changed = false,
          .message = "Maestro over native USB: " + cause +
                     ". The serial timeout and home positions are NOT set by the agent: if it "
                     "dies, the servos may hold their last position instead of parking. Fix "
                     "the cause, or " +
                     ManualAdvice(settings) + ". Flying on; servo commands use the serial port.",
          .ranges = {}};
}

bool Read(MaestroUsbPort& port, const MaestroParameter& parameter, std::uint16_t* value,
          std::string* error) {
  std::vector<std::uint8_t> bytes;
  if (!port.Transfer(GetParameterTransfer(parameter), &bytes, error)) {
    *error = "cannot read " + parameter.name + " (" + *error + ")";
    return false;
  }
  *value = ParameterValue(bytes);
  return true;
}

// The wanted parameters whose current value differs, and "name old → new" for each.
bool FindDiffering(MaestroUsbPort& port, const std::vector<MaestroParameter>& wanted,
                   std::vector<MaestroParameter>* differing, std::string* changes,
                   std::string* cause) {
  for (const MaestroParameter& parameter : wanted) {
    std::uint16_t current = 0;
    if (!Read(port, parameter, &current, cause)) return false;
    if (current == parameter.value) continue;
    differing->push_back(parameter);
    if (!changes->empty()) *changes += ", ";
    *changes += parameter.name + " " + DescribeParameterValue(parameter, current) + " → " +
                DescribeParameterValue(parameter, parameter.value);
  }
  return true;
}

// Writes the differing parameters and reinitializes the Maestro so that they take effect.
bool WriteDiffering(MaestroUsbPort& port, const std::vector<MaestroParameter>& differing,
                    std::string* cause) {
  for (const MaestroControlTransfer& transfer : MaestroSettingsTransfers(differing)) {
    std::vector<std::uint8_t> unused;
    std::string reason;
    if (!port.Transfer(transfer, &unused, &reason)) {
      *cause = transfer.request == maestro::kRequestReinitialize ? "cannot reinitialize it ("
                                                                 : "cannot write a parameter (";
      *cause += reason;
      *cause += ")";
      return false;
    }
  }
  if (!differing.empty()) {
    std::this_thread::sleep_for(std::chrono::milliseconds(kReinitializeWaitMs));
  }
  return true;
}

// Reads every wanted parameter back; `values` lists them as "name value".
bool VerifyReadBack(MaestroUsbPort& port, const std::vector<MaestroParameter>& wanted,
                    std::string* values, std::string* cause) {
  for (const MaestroParameter& parameter : wanted) {
    std::uint16_t back = 0;
    if (!Read(port, parameter, &back, cause)) return false;
    if (back != parameter.value) {
      *cause = parameter.name + " reads back as " + DescribeParameterValue(parameter, back) +
               " after writing " + DescribeParameterValue(parameter, parameter.value);
      return false;
    }
    if (!values->empty()) *values += ", ";
    *values += parameter.name + " " + DescribeParameterValue(parameter, parameter.value);
  }
  return true;
}

// The channels' own Min/Max are read only: they are the user's calibration of the servos,
// which the agent checks its mapping against (MaestroServoDriver) but never overwrites.
bool ReadChannelRanges(MaestroUsbPort& port, const std::vector<MaestroHome>& homes,
                       std::vector<MaestroChannelRange>* ranges, std::string* cause) {
  for (const MaestroHome& home : homes) {
    std::uint16_t low = 0;
    std::uint16_t high = 0;
    if (!Read(port, ChannelMinParameter(home.channel), &low, cause) ||
        !Read(port, ChannelMaxParameter(home.channel), &high, cause)) {
      return false;
    }
    // [64 quarter-µs] = 16 µs per unit.
    ranges->push_back({.channel = home.channel, .min_us = low * 16.0, .max_us = high * 16.0});
  }
  return true;
}

}  // namespace

MaestroUsbSetupResult ApplyMaestroUsbSettings(MaestroUsbPort& port,
                                              const MaestroUsbSettings& settings) {
  std::string reason;
  if (!settings.IsValid(&reason)) return Failure(settings, "invalid settings: " + reason);
  if (!port.Open(&reason)) return Failure(settings, reason);
  struct Closer {
    MaestroUsbPort& port;
    ~Closer() { port.Close(); }
  } closer{port};

  const std::string device = port.Describe();
  auto fail_at_device = [&settings, &device](const std::string& cause) {
    std::string text = device;
    text += ": ";
    text += cause;
    return Failure(settings, text);
  };
  const int channels = maestro::ChannelCount(port.product_id());
  for (const MaestroHome& home : settings.homes) {
    if (home.channel >= channels) {
      return fail_at_device("it has " + std::to_string(channels) + " channels, no channel " +
                            std::to_string(home.channel));
    }
  }

  std::vector<MaestroParameter> wanted = MaestroSettingsParameters(settings);
  wanted.push_back(SerialModeParameter());
  std::vector<MaestroParameter> differing;
  std::string changes;
  std::string values;
  std::vector<MaestroChannelRange> ranges;
  if (!FindDiffering(port, wanted, &differing, &changes, &reason) ||
      !WriteDiffering(port, differing, &reason) ||
      !VerifyReadBack(port, wanted, &values, &reason) ||
      !ReadChannelRanges(port, settings.homes, &ranges, &reason)) {
    return fail_at_device(reason);
  }

  MaestroUsbSetupResult result{
      .ok = true, .changed = !differing.empty(), .message = "", .ranges = ranges};
  result.message = "Maestro over native USB, " + device + ": " + values +
                   (differing.empty() ? " (already set; nothing written)"
                                      : " (written: " + changes + "; reinitialized)") +
                   ", read back and verified. With no serial command for the timeout, the "
                   "Maestro sends these channels home.";
  return result;
}

}  // namespace kapfix::agent
