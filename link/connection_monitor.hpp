#pragma once

// Server side of the link (includes ZeroMQ): watches one server socket's connections
// through libzmq's socket monitor, on its own thread (issue 15, items 3 and 11).
// - Connection budget: at most max_connections at once. A connection accepted beyond it makes
//   room by shutting down the oldest open one that has not sent a whole ZMTP greeting (64
//   bytes, from the kernel's TCP_INFO): that one cannot be a station yet. Only when every open
//   connection has (stations, peers in their handshake) is the newcomer shut down. Descriptors
//   are libzmq's: shutdown(), not close(), so libzmq sees the end and frees them. Together with
//   ZMQ_HANDSHAKE_IVL, which closes a connection that stays silent, and the raised open-file
//   limit, a flood of silent connections cannot keep an authorised station out nor take the
//   descriptors a photo needs.
// - Refused handshakes (garbage, forged keys, protocol errors; ZAP refusals too) are logged in
//   one summary line per period, whatever their number or source, so a peer cannot flood the
//   log (nor the stations, which receive the log lines).

#include <atomic>
#include <chrono>
#include <cstdint>
#include <string>
#include <thread>
#include <zmq.hpp>

namespace kapfix::link {

struct ConnectionMonitorOptions {
  std::size_t max_connections = 4096;                // [count] at once, on this socket
  std::chrono::milliseconds summary_period{10'000};  // [ms] at most one log line per period
};

class ConnectionMonitor {
 public:
  struct Counters {
    std::uint64_t accepted = 0;           // [count] TCP connections accepted
    std::uint64_t over_budget = 0;        // [count] shut down over the budget (newcomer
                                          // or a silent one making room)
    std::uint64_t handshakes_failed = 0;  // [count] ZMTP/CurveZMQ handshakes refused
  };

  // `what` names the server in log lines.
  ConnectionMonitor(std::string what, ConnectionMonitorOptions options);
  ~ConnectionMonitor();  // joins: shut the context down first
  ConnectionMonitor(const ConnectionMonitor&) = delete;
  ConnectionMonitor& operator=(const ConnectionMonitor&) = delete;

  // Call on the socket's own thread, before it binds. Throws zmq::error_t.
  void Start(zmq::context_t& context, zmq::socket_t& socket);

  Counters counters() const;

 private:
  void Serve(zmq::socket_t& events);

  std::string what_;
  ConnectionMonitorOptions options_;
  std::thread thread_;
  std::atomic<std::uint64_t> accepted_{0};
  std::atomic<std::uint64_t> over_budget_{0};
  std::atomic<std::uint64_t> handshakes_failed_{0};
};

}  // namespace kapfix::link
