#pragma once

// Internal to kapfix_agent_server (includes ZeroMQ): binds a server socket either on its
// endpoint or, for a tcp:// endpoint with an intake configured, behind a link::BoundedIntake
// (issue 15, item 4): the socket binds a unix socket in a fresh directory only the agent's
// user can enter (mode 0700), and the intake listens on the endpoint and relays each peer.

#include <chrono>
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <zmq.hpp>

#include "link/bounded_intake.hpp"
#include "link/link_endpoint.hpp"
#include "link/whole_message_receive.hpp"

namespace kapfix::agent {

class IntakeBinding {
 public:
  IntakeBinding() = default;
  ~IntakeBinding();  // Close()s
  IntakeBinding(const IntakeBinding&) = delete;
  IntakeBinding& operator=(const IntakeBinding&) = delete;

  // Binds `socket` and returns the endpoint peers connect to. `intake` unset, or an endpoint
  // that is not tcp://: the socket binds `endpoint` itself. `what` names the socket in logs.
  // Throws zmq::error_t or std::runtime_error.
  std::string Bind(zmq::socket_t& socket, const link::LinkEndpoint& endpoint,
                   const std::optional<link::BoundedIntakeOptions>& intake,
                   std::size_t max_connections, const std::string& what);
  // Stops the intake and removes the private directory; idempotent.
  void Close();

  bool active() const { return intake_ != nullptr; }
  // Tells the intake what the socket received (no-op without one).
  void Consumed(const link::ReceivedWire& wire) const;
  // Ends the connection behind `fd` (ZMQ_SRCFD): at the intake, which then relays nothing more
  // of it, and on libzmq's descriptor (shutdown(), not close(): libzmq frees it).
  void Disconnect(int fd) const;
  // Reads nothing more of the peer behind `fd` (ZMQ_SRCFD) until `until` (no-op without an
  // intake): what it sends meanwhile waits in the kernel's socket buffers.
  void Hold(int fd, std::chrono::steady_clock::time_point until) const;
  // The peer's real address behind `fd` (ZMQ_SRCFD); empty without an intake.
  std::string PeerAddressOf(int fd) const;
  // The intake's counters; zero without one.
  link::BoundedIntake::Counters counters() const;

 private:
  std::unique_ptr<link::BoundedIntake> intake_;
  std::string directory_;
  std::string path_;
};

}  // namespace kapfix::agent
