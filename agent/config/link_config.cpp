#include "agent/config/link_config.hpp"

#include <cctype>
#include <string_view>

namespace kapfix::agent {
namespace {

bool IsPort(std::string_view text) {
  if (text.empty() || text.size() > 5) return false;
  int port = 0;
  for (const char c : text) {
    if (!std::isdigit(static_cast<unsigned char>(c))) return false;
    port = port * 10 + (c - '0');
  }
  return port >= 1 && port <= 65535;
}

bool IsAddress(std::string_view a) {
  constexpr std::string_view kTcp = "tcp://";
  if (a.substr(0, kTcp.size()) == kTcp) {
    const std::string_view rest = a.substr(kTcp.size());
    const std::size_t colon = rest.rfind(':');
    return colon != std::string_view::npos && colon > 0 && IsPort(rest.substr(colon + 1));
  }
  for (const std::string_view scheme :
       {std::string_view("ipc://"), std::string_view("inproc://")}) {
    if (a.size() > scheme.size() && a.substr(0, scheme.size()) == scheme) return true;
  }
  return false;
}

}  // namespace

bool LinkConfig::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!IsAddress(command_address)) {
    return fail("link.command: '" + command_address +
                "' is not tcp://HOST:PORT, ipc://PATH or inproc://NAME");
  }
  if (!IsAddress(stream_address)) {
    return fail("link.stream: '" + stream_address +
                "' is not tcp://HOST:PORT, ipc://PATH or inproc://NAME");
  }
  if (command_address == stream_address) {
    return fail("link.stream: must differ from link.command (" + command_address + ")");
  }
  if (heartbeat_ms < 100 || heartbeat_ms > 60000) {
    return fail("link.heartbeat_ms: must be 100…60000 ms, got " + std::to_string(heartbeat_ms));
  }
  if (!(command_rate_per_s >= 0.1 && command_rate_per_s <= 100'000)) {
    return fail("link.command_rate_per_s: must be 0.1…100000 commands/s, got " +
                std::to_string(command_rate_per_s));
  }
  if (!(command_burst >= 1 && command_burst <= 1'000'000)) {
    return fail("link.command_burst: must be 1…1000000 commands, got " +
                std::to_string(command_burst));
  }
  if (!(all_commands_rate_per_s >= command_rate_per_s && all_commands_rate_per_s <= 100'000 &&
        2 * all_commands_rate_per_s >= command_burst)) {
    return fail(
        "link.all_commands_rate_per_s: must be at least link.command_rate_per_s and "
        "half link.command_burst, at most 100000 commands/s, got " +
        std::to_string(all_commands_rate_per_s));
  }
  if (curve_secret_key_file.empty() != curve_authorized_keys_file.empty()) {
    return fail("link.curve_authorized_keys_file: set both CURVE files or neither");
  }
  return true;
}

}  // namespace kapfix::agent
