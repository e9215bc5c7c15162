#pragma once

// The agent's command socket (SPEC §5): a ROUTER on its own thread that answers every request
// with exactly one stamped Reply, OK or an error naming the problem, and never dies on what a
// station sends. Also answers station heartbeats with an echo, from which the station
// measures the round-trip latency.
//
// Wire format, after the routing id that ROUTER adds: an optional empty delimiter frame (a
// REQ socket sends one; the reply copies it), an optional topic frame ("command" or
// "heartbeat"; the reply then carries "reply" or "heartbeat"), and the serialized message.

#include <chrono>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "agent/server/agent_control.hpp"
#include "agent/server/command_rate_limit.hpp"
#include "agent/server/command_validator.hpp"
#include "agent/server/replay_window.hpp"
#include "agent/server/subscriber_loss_book.hpp"
#include "kapfix/v1/envelope_codec.hpp"
#include "link/bounded_intake.hpp"
#include "link/curve_server_keys.hpp"

namespace kapfix::agent {

struct CommandServerOptions {
  // ZeroMQ endpoint to bind; "tcp://127.0.0.1:*" binds an ephemeral port (see Start()).
  std::string bind_endpoint = "tcp://*:5555";
  std::string agent_id = "kapfix-agent";  // header.agent_id of every reply
  std::uint64_t boot_id = 0;              // header.boot_id of every reply (DrawBootId)
  // [bytes] ZMQ_MAXMSGSIZE: libzmq drops the connection of a peer that sends a larger frame,
  // without delivering it, so no reply can name the problem. Commands up to this size are
  // read, and those above kMaxCommandBytes refused with ERROR_CODE_OVERSIZED; the margin
  // above kMaxCommandBytes is what lets a slightly oversized command get its error reply.
  std::int64_t transport_limit_bytes = 4 * static_cast<std::int64_t>(kapfix::v1::kMaxCommandBytes);
  // [ms] ZeroMQ heartbeats (ZMTP PING) on each connection: a station that vanished without
  // closing its TCP connection (WiFi gone) is dropped after heartbeat_timeout.
  std::chrono::milliseconds zmtp_heartbeat_interval{1000};
  std::chrono::milliseconds zmtp_heartbeat_timeout{3000};
  // [ms] ZMQ_HANDSHAKE_IVL: a connection that has not completed its ZMTP (and CurveZMQ)
  // handshake within this is closed (libzmq's default keeps a silent one 30 s), so silent
  // connections cannot hold the agent's file descriptors.
  std::chrono::milliseconds handshake_timeout{2000};
  CommandLimits limits;
  // Replay protection across connections (ReplayWindow); unset: per connection only.
  std::optional<ReplayWindowOptions> replay = ReplayWindowOptions{};
  // [count] connections at once; one accepted beyond this is closed at once (keep it under
  // the open-file limit, with room for the agent's own files).
  std::size_t max_connections = 4096;
  // CurveZMQ: encrypt every connection and accept only the listed stations. Unset: plain.
  std::optional<kapfix::link::CurveServerKeys> curve;
  // Issue 15: a tcp:// endpoint is listened on by a link::BoundedIntake that relays each peer
  // to the socket (bound on a private unix socket) and stops reading a peer that has sent
  // `budget_bytes` the server has not received as whole messages (its endpoint fields are
  // filled in by the server). Unset: the socket binds the endpoint itself, and an unfinished
  // multipart message is held whole.
  std::optional<link::BoundedIntakeOptions> intake =
      link::IntakeWithBudget(4 * static_cast<std::uint64_t>(4 * kapfix::v1::kMaxCommandBytes));
  // Issue 15: what each station reports lost of the streams in its heartbeats (Heartbeat.lost).
  SubscriberLossBookOptions subscriber_losses;
  // Issue 15: commands beyond these rates are refused with ERROR_CODE_RATE_LIMITED before
  // they are decoded or validated, and (behind the intake) the station's connection is not
  // read again until its bucket has a token, so a flood costs the agent about one refusal per
  // token interval. Unset: no limit. Must be IsValid (Start() throws otherwise).
  std::optional<CommandRateLimitOptions> rate_limit = CommandRateLimitOptions{};
};

class CommandServer {
 public:
  struct Counters {
    std::uint64_t commands_ok = 0;            // [count] replies with ok = true
    std::uint64_t commands_refused = 0;       // [count] error replies, whatever the cause
    std::uint64_t commands_rate_limited = 0;  // [count] of those: ERROR_CODE_RATE_LIMITED
    std::uint64_t heartbeats_echoed = 0;      // [count] station heartbeats answered
    std::uint64_t heartbeats_ignored = 0;     // [count] malformed or replayed heartbeats
    std::int64_t last_station_heard_us = 0;   // [µs since epoch] last accepted command or
                                              // heartbeat; 0 = never (link-loss detection)
    std::uint64_t keys_refused = 0;           // [count] CurveZMQ handshakes refused (unknown key)
    std::uint64_t handshakes_failed = 0;      // [count] ZMTP/CurveZMQ handshakes that failed
    std::uint64_t over_budget = 0;            // [count] connections shut down over the budget
    std::uint64_t intake_paused = 0;          // [count] times a peer reached its byte budget
    std::uint64_t intake_closed = 0;          // [count] peers closed for staying at it
  };

  // `control` must outlive the server (or at least Stop()).
  CommandServer(AgentControl& control, CommandServerOptions options = {});
  ~CommandServer();  // Stop()s
  CommandServer(const CommandServer&) = delete;
  CommandServer& operator=(const CommandServer&) = delete;

  // Starts the thread, binds, and returns the bound endpoint (ZMQ_LAST_ENDPOINT, e.g.
  // "tcp://127.0.0.1:41234"). Throws std::runtime_error when binding fails (address in use,
  // bad endpoint), when the rate limit is not IsValid, or when already started.
  std::string Start();
  // Returns promptly (shuts the server's ZeroMQ context down); idempotent. Requests in flight
  // get no reply.
  void Stop();

  Counters counters() const;
  // What each station last reported lost of the streams, per topic (its CurveZMQ key's name;
  // "at <address>" for a plain one), most recently heard first. Thread-safe.
  std::vector<StationLosses> SubscriberLosses() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kapfix::agent
