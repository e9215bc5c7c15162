#pragma once

// Internal to kapfix_link's client (includes ZeroMQ): why the agent would not let this station
// in. A CurveZMQ refusal happens inside ZeroMQ's handshake, where no reply can carry a reason;
// the socket's monitor events are the only trace of it, and an operator with a wrong key
// deserves better than "no answer".

#include <string>
#include <zmq.hpp>

namespace kapfix::link {

class HandshakeMonitor final : public zmq::monitor_t {
 public:
  // Watches `socket`'s handshakes (`name` makes the inproc address unique in its context).
  HandshakeMonitor(zmq::socket_t& socket, const std::string& name);

  // Reads the events that arrived, without waiting.
  void Poll();
  // Why the last handshake failed; empty when none failed since the last success.
  const std::string& failure() const { return failure_; }

 private:
  void on_event_handshake_failed_no_detail(const zmq_event_t& event, const char* address) override;
  void on_event_handshake_failed_protocol(const zmq_event_t& event, const char* address) override;
  void on_event_handshake_failed_auth(const zmq_event_t& event, const char* address) override;
  void on_event_handshake_succeeded(const zmq_event_t& event, const char* address) override;

  std::string failure_;
};

}  // namespace kapfix::link
