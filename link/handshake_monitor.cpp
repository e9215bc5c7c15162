#include "link/handshake_monitor.hpp"

#include <sstream>

namespace kapfix::link {
namespace {

constexpr int kHandshakeEvents = ZMQ_EVENT_HANDSHAKE_FAILED_NO_DETAIL |
                                 ZMQ_EVENT_HANDSHAKE_FAILED_PROTOCOL |
                                 ZMQ_EVENT_HANDSHAKE_FAILED_AUTH | ZMQ_EVENT_HANDSHAKE_SUCCEEDED;

}  // namespace

HandshakeMonitor::HandshakeMonitor(zmq::socket_t& socket, const std::string& name) {
  init(socket, "inproc://kapfix-handshake-" + name, kHandshakeEvents);
}

void HandshakeMonitor::Poll() {
  while (check_event(0)) {
  }
}

void HandshakeMonitor::on_event_handshake_failed_no_detail(const zmq_event_t& /*event*/,
                                                           const char* address) {
  failure_ = std::string("the security handshake with ") + address +
             " failed: check the agent's public key (--agent-key) and that both ends use, or "
             "both do not use, CurveZMQ keys";
}

void HandshakeMonitor::on_event_handshake_failed_protocol(const zmq_event_t& event,
                                                          const char* address) {
  if (event.value == ZMQ_PROTOCOL_ERROR_ZMTP_MECHANISM_MISMATCH) {
    failure_ = std::string("the security handshake with ") + address +
               " failed: one end uses CurveZMQ keys and the other does not (--key and "
               "--agent-key here, link.curve_secret_key_file on the agent)";
    return;
  }
  std::ostringstream code;
  code << std::hex << event.value;
  failure_ = std::string("the security handshake with ") + address +
             " failed (ZeroMQ protocol error 0x" + code.str() +
             "): check the agent's public key (--agent-key)";
}

void HandshakeMonitor::on_event_handshake_failed_auth(const zmq_event_t& /*event*/,
                                                      const char* address) {
  failure_ = std::string("the agent at ") + address +
             " refused this station's key: add its .pub line to the agent's authorised keys "
             "file (link.curve_authorized_keys_file)";
}

void HandshakeMonitor::on_event_handshake_succeeded(const zmq_event_t& /*event*/,
                                                    const char* /*address*/) {
  failure_.clear();
}

}  // namespace kapfix::link
