#pragma once

// One ZeroMQ endpoint to bind, parsed strictly (issue 15, item 2), so that the rule "no keys,
// loopback only" cannot be bypassed by what libzmq would read differently from a prefix check:
// - libzmq reads "tcp://A;B" as "bind B, source A": refused (no ';' at all, one endpoint only);
// - "tcp://localhost:P" passed a prefix check but libzmq cannot bind it: resolved to
//   127.0.0.1 here;
// - a host that is neither an IP literal, '*' nor localhost (an interface name such as "eth0",
//   "127.0.0.1.example.org") is refused: only a literal can be judged loopback or not;
// - "127.1", "0x7f000001" and other inet_aton spellings are refused (inet_pton only).
// The endpoint handed to libzmq is the canonical one rebuilt from the parsed parts, never the
// text as given.

#include <optional>
#include <string>
#include <string_view>

namespace kapfix::link {

struct LinkEndpoint {
  std::string canonical;  // e.g. "tcp://127.0.0.1:5555", "tcp://*:0", "ipc:///run/kapfix"
  bool loopback = false;  // reachable from this machine only (127/8, ::1, ipc, inproc)
};

// The endpoint, or std::nullopt with a one-line reason in `error` naming the problem.
// Accepted: tcp://HOST:PORT with HOST an IPv4 literal, [IPv6 literal], '*' or localhost and
// PORT 0…65535 or '*'; ipc://PATH; inproc://NAME.
std::optional<LinkEndpoint> ParseLinkEndpoint(std::string_view text, std::string* error);

}  // namespace kapfix::link
