#include "link/link_endpoint.hpp"

#include <arpa/inet.h>

#include <array>
#include <cctype>

namespace kapfix::link {
namespace {

constexpr std::string_view kTcp = "tcp://";
constexpr std::string_view kIpc = "ipc://";
constexpr std::string_view kInproc = "inproc://";

bool IsPort(std::string_view text) {
  if (text == "*") return true;
  if (text.empty() || text.size() > 5) return false;
  int port = 0;
  for (const char c : text) {
    if (std::isdigit(static_cast<unsigned char>(c)) == 0) return false;
    port = port * 10 + (c - '0');
  }
  return port <= 65535;
}

std::optional<LinkEndpoint> Fail(std::string_view text, const std::string& why,
                                 std::string* error) {
  if (error != nullptr) *error = "link address '" + std::string(text) + "': " + why;
  return std::nullopt;
}

}  // namespace

std::optional<LinkEndpoint> ParseLinkEndpoint(std::string_view text, std::string* error) {
  for (const char c : text) {
    if (c == ';') {
      return Fail(text, "';' is not allowed (libzmq would read 'A;B' as bind B from source A)",
                  error);
    }
    if (c == ',' || std::isspace(static_cast<unsigned char>(c)) != 0 ||
        std::iscntrl(static_cast<unsigned char>(c)) != 0) {
      return Fail(text, "exactly one endpoint, without spaces or separators", error);
    }
  }
  for (const std::string_view scheme : {kIpc, kInproc}) {
    if (text.starts_with(scheme)) {
      if (text.size() == scheme.size()) return Fail(text, "empty path", error);
      return LinkEndpoint{std::string(text), true};
    }
  }
  if (!text.starts_with(kTcp)) return Fail(text, "expected tcp://, ipc:// or inproc://", error);
  const std::string_view rest = text.substr(kTcp.size());
  const std::size_t colon = rest.rfind(':');
  if (colon == std::string_view::npos || colon == 0) {
    return Fail(text, "expected tcp://HOST:PORT", error);
  }
  const std::string_view host = rest.substr(0, colon);
  const std::string_view port = rest.substr(colon + 1);
  if (!IsPort(port)) return Fail(text, "port must be 0…65535 or '*'", error);
  const std::string port_text(port);
  if (host == "*") return LinkEndpoint{"tcp://*:" + port_text, false};
  if (host == "localhost") return LinkEndpoint{"tcp://127.0.0.1:" + port_text, true};
  std::array<unsigned char, 16> bytes{};
  if (host.size() > 2 && host.front() == '[' && host.back() == ']') {
    const std::string literal(host.substr(1, host.size() - 2));
    if (inet_pton(AF_INET6, literal.c_str(), bytes.data()) != 1) {
      return Fail(text, "'" + literal + "' is not an IPv6 address", error);
    }
    std::array<char, INET6_ADDRSTRLEN> canonical{};
    inet_ntop(AF_INET6, bytes.data(), canonical.data(), canonical.size());
    const bool loopback = std::string_view(canonical.data()) == "::1";
    return LinkEndpoint{"tcp://[" + std::string(canonical.data()) + "]:" + port_text, loopback};
  }
  const std::string literal(host);
  if (inet_pton(AF_INET, literal.c_str(), bytes.data()) != 1) {
    return Fail(text,
                "host '" + literal +
                    "' must be an IPv4 address in dotted quads, [IPv6], '*' or localhost "
                    "(interface and host names are not accepted)",
                error);
  }
  std::array<char, INET_ADDRSTRLEN> canonical{};
  inet_ntop(AF_INET, bytes.data(), canonical.data(), canonical.size());
  return LinkEndpoint{"tcp://" + std::string(canonical.data()) + ":" + port_text, bytes[0] == 127};
}

}  // namespace kapfix::link
