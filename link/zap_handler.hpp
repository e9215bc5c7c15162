#pragma once

// Server side of the link (includes ZeroMQ): the ZAP handler (ZeroMQ RFC 27) that
// decides, for every CurveZMQ handshake on a server's context, whether the station's public
// key is authorised. It runs on its own thread with its own REP socket, bound to
// inproc://zeromq.zap.01 in that context before the server socket binds.
//
// Fail closed: the server sockets set ZAP_ENFORCE_DOMAIN, so a handshake that gets no answer
// from a handler is refused, not let through; and only the "kapfix" domain, the CURVE
// mechanism and listed keys are accepted.

#include <atomic>
#include <cstdint>
#include <string>
#include <thread>
#include <unordered_map>
#include <zmq.hpp>

#include "link/curve_server_keys.hpp"

namespace kapfix::link {

inline constexpr const char* kZapDomain = "kapfix";

// Makes `socket` a CURVE server with the agent's key that asks the ZAP handler about every
// connection. Throws zmq::error_t when ZeroMQ refuses an option.
void RequireCurve(zmq::socket_t& socket, const CurveServerKeys& keys);

class ZapHandler {
 public:
  struct Counters {
    std::uint64_t accepted = 0;  // [count] handshakes with an authorised key
    std::uint64_t refused = 0;   // [count] any other request
  };

  // `what` names the server in log lines ("command server", "stream publisher").
  ZapHandler(const CurveServerKeys& keys, std::string what);
  ~ZapHandler();  // joins: shut the context down first
  ZapHandler(const ZapHandler&) = delete;
  ZapHandler& operator=(const ZapHandler&) = delete;

  // Binds in `context` and starts the thread; throws std::runtime_error when the bind fails
  // (another handler already bound in that context).
  void Start(zmq::context_t& context);
  // Waits for the thread, which ends when the context is shut down.
  void Join();

  Counters counters() const;

 private:
  void Serve(zmq::socket_t& socket);
  bool Decide(const std::vector<zmq::message_t>& request, std::string* user,
              std::string* why) const;

  std::unordered_map<std::string, std::string> stations_;  // Z85 public key → name
  std::string what_;
  std::thread thread_;
  std::atomic<std::uint64_t> accepted_{0};
  std::atomic<std::uint64_t> refused_{0};
};

}  // namespace kapfix::link
