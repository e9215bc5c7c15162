#pragma once

// A bounded intake in front of one of the agent's ZeroMQ sockets (issue 15, item 4).
//
// libzmq assembles a whole multipart message in its pipe before the application sees its first
// frame (ZMQ_MAXMSGSIZE is per frame, ZMQ_RCVHWM counts whole messages), so a peer that sends
// frames and never the last one makes the agent hold all it sends. The intake accepts the
// public TCP endpoint itself, on its own epoll thread, and relays each peer's bytes, untouched
// (CurveZMQ stays end to end), over a connection of its own to the agent's socket, which binds
// a unix socket in a directory only the agent's user can enter. Per peer it counts the bytes
// relayed to the agent; the agent reports, for each message it receives, the bytes that message
// took on the wire (Consumed). When what was relayed and not consumed reaches the budget, the
// intake stops reading the peer (its bytes then wait in the kernel's socket buffers) until a
// quarter of the budget is free again, and closes it if that lasts over_budget_limit. An unfinished
// message of any length thus holds at most the budget in the agent, plus the allowance for ZMTP's
// own traffic (greeting, handshake, heartbeats) that no message accounts for.
//
// Each of the intake's connections to the agent is bound to a unique abstract unix address
// before it connects: the agent finds a received message's peer by getpeername() on the
// message's ZMQ_SRCFD. The intake also keeps the connection budget (the agent's socket only
// sees unix connections) and knows each peer's real address.

#include <chrono>
#include <cstdint>
#include <memory>
#include <string>

namespace kapfix::link {

struct BoundedIntakeOptions {
  // Where peers connect: "tcp://HOST:PORT" as ParseLinkEndpoint makes it canonical
  // (HOST an IP literal, [IPv6] or '*'; PORT 0 or '*' for an ephemeral one).
  std::string public_endpoint;
  // The unix socket the agent's ZeroMQ socket binds ("ipc://" + this).
  std::string private_path;
  // [bytes] relayed to the agent and not yet consumed, per peer; a few times the largest
  // message the socket accepts whole.
  std::uint64_t budget_bytes = std::uint64_t{1} << 20U;
  // [bytes/s] credited to each peer for traffic that is no message: ZMTP greeting, handshake
  // and heartbeats (about 60 bytes a second with CurveZMQ).
  std::uint64_t allowance_bytes_per_s = 256;
  // [ms] a peer that stays at its budget this long is closed.
  std::chrono::milliseconds over_budget_limit{10'000};
  // [count] peers at once. Beyond it a newcomer makes room by closing the oldest peer that has
  // not sent a whole ZMTP greeting (64 bytes), which cannot be a station yet; when every peer
  // has, the newcomer is closed.
  std::size_t max_connections = 4096;
  // [ms] at most one log line per period about closed peers.
  std::chrono::milliseconds log_period{10'000};
  std::string what = "intake";  // names the socket in log lines
  bool IsValid(std::string* error) const;
};

// The default options with another budget.
inline BoundedIntakeOptions IntakeWithBudget(std::uint64_t budget_bytes) {
  BoundedIntakeOptions options;
  options.budget_bytes = budget_bytes;
  return options;
}

class BoundedIntake {
 public:
  struct Counters {
    std::uint64_t accepted = 0;            // [count] TCP connections accepted
    std::uint64_t over_connections = 0;    // [count] closed over the connection budget
    std::uint64_t paused = 0;              // [count] times a peer reached its byte budget
    std::uint64_t closed_over_budget = 0;  // [count] closed after over_budget_limit at it
    std::uint64_t open = 0;                // [count] peers now relayed
    std::uint64_t held = 0;                // [count] holds asked for (Hold)
  };

  explicit BoundedIntake(BoundedIntakeOptions options);
  ~BoundedIntake();  // Stop()s
  BoundedIntake(const BoundedIntake&) = delete;
  BoundedIntake& operator=(const BoundedIntake&) = delete;

  // Binds the public endpoint, starts the thread and returns the bound endpoint, e.g.
  // "tcp://127.0.0.1:41234". The agent's socket must be bound on private_path first. Throws
  // std::runtime_error naming the problem.
  std::string Start();
  // Closes every peer and joins the thread; idempotent.
  void Stop();

  // The agent received a message taking `wire_bytes` (ZmtpWireBytes of its frames) from the
  // connection that is `agent_fd` on its side (ZMQ_SRCFD). Thread-safe; a descriptor that is
  // no connection of this intake is ignored.
  void Consumed(int agent_fd, std::uint64_t wire_bytes);
  // Closes the peer behind `agent_fd` (the agent refuses what it sent), before it can send
  // more. Thread-safe; a descriptor that is none of this intake's is ignored.
  void Disconnect(int agent_fd);
  // Reads nothing more from the peer behind `agent_fd` until `until` (at most kMaxHold from
  // now): what it sends meanwhile waits in the kernel's socket buffers, and costs the agent
  // nothing. The agent holds a station that sends commands faster than its rate until its
  // next token. Bytes already relayed are still delivered. Thread-safe; a descriptor that is
  // none of this intake's is ignored.
  void Hold(int agent_fd, std::chrono::steady_clock::time_point until);
  // [ms] the longest hold: well under ZeroMQ's heartbeat timeout, so a held station's
  // PONGs are late, never missed.
  static constexpr std::chrono::milliseconds kMaxHold{1000};
  // "HOST:PORT" of the peer behind `agent_fd`; empty when it is none of this intake's.
  std::string PeerAddressOf(int agent_fd) const;

  Counters counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// [bytes] one message frame of `frame_bytes` as ZMTP 3 carries it: flags and size (2 or 9
// bytes) and, with CurveZMQ, the MESSAGE command around its box (33 bytes).
std::uint64_t ZmtpWireBytes(std::uint64_t frame_bytes, bool curve);

}  // namespace kapfix::link
