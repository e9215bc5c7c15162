#pragma once

// The station's side of the link (SPEC §5), shared by kapfix-ctl and kapfix-station: Qt-free,
// one I/O thread that owns both ZeroMQ sockets.
// - Commands: a DEALER to the agent's ROUTER. Each request gets the next sequence number of
//   this connection and waits for its reply until a deadline; a command that could not even
//   be sent before its deadline is never sent later (a late servo command is worse than none).
// - Streams: a SUB to the agent's PUB, one handler per topic, plus an optional raw handler
//   that sees every message's bytes (recording).
// - Heartbeats: sent on the DEALER every heartbeat_interval; the agent echoes each, which
//   gives the round-trip latency. Each carries what this station lost of each stream topic
//   (Heartbeat.lost), so the agent knows which station reads too slowly. The link is up while
//   anything valid arrived from the agent within link_timeout (its periodic heartbeats on the PUB
//   keep it up when idle).
// - Reconnection is ZeroMQ's: both sockets reconnect by themselves; ZMTP heartbeats drop a
//   dead TCP connection so that reconnection starts.
//
// Handlers run on the I/O thread: keep them short, and never call Request() from one (a GUI
// posts the message to its own thread).

#include <google/protobuf/message.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "kapfix/v1/command.pb.h"
#include "link/curve_key_pair.hpp"

namespace kapfix::link {

struct AgentLinkClientOptions {
  std::string command_endpoint = "tcp://localhost:5555";
  std::string stream_endpoint = "tcp://localhost:5556";
  // Written into header.agent_id of commands: the agent refuses a command addressed to
  // another id. Empty: whichever agent listens there.
  std::string agent_id;
  std::chrono::milliseconds heartbeat_interval{1000};
  // Three missed heartbeats: SPEC §5 / issue 5 want link loss shown within 3.5 s.
  std::chrono::milliseconds link_timeout{3000};
  std::chrono::milliseconds zmtp_heartbeat_interval{1000};
  std::chrono::milliseconds zmtp_heartbeat_timeout{3000};
  // [messages] ZMQ_RCVHWM of the stream socket: what ZeroMQ holds for this station before it
  // stops reading the connection (the agent then drops this station's messages, counted in
  // LinkStatus::sequence_gaps).
  int stream_receive_high_water_mark = 1000;
  // Unset: plain ZMTP, which an agent with keys refuses.
  std::optional<CurveClientKeys> curve;
};

struct LinkStatus {
  bool up = false;                      // something valid arrived within link_timeout
  std::int64_t last_heard_us = 0;       // [µs since epoch, this side's clock] 0 = never
  std::int64_t latency_us = -1;         // [µs] round trip of the last echoed heartbeat; -1 = none
  std::string agent_id;                 // as the agent's messages say
  std::uint64_t messages_received = 0;  // [count] valid stream messages
  std::uint64_t messages_invalid = 0;   // [count] stream messages that failed to decode
  // [count] stream messages this station lost (StreamLossCounter): gaps in the per-topic
  // sequence numbers, and the tail of a burst, which the agent's next periodic heartbeat shows
  // (the agent numbers what it hands to ZeroMQ, so either is a loss on the link, including
  // what was published while this station was disconnected). Sent back to the agent in this
  // station's heartbeats (Heartbeat.lost), per topic.
  std::uint64_t sequence_gaps = 0;
  // Why the agent did not let this station in (a refused key, a wrong agent key, one end
  // without keys); empty while the last handshake succeeded or none failed.
  std::string handshake_failure;
};

class AgentLinkClient {
 public:
  using MessageHandler = std::function<void(const google::protobuf::Message& message)>;
  using RawHandler = std::function<void(std::string_view topic, std::string_view payload)>;
  using ReplyHandler = std::function<void(std::optional<kapfix::v1::Reply> reply)>;
  using LinkHandler = std::function<void(bool up)>;

  explicit AgentLinkClient(AgentLinkClientOptions options = {});
  ~AgentLinkClient();  // Stop()s
  AgentLinkClient(const AgentLinkClient&) = delete;
  AgentLinkClient& operator=(const AgentLinkClient&) = delete;

  // Before Start() only (subscriptions are set when the SUB socket connects). `topic` is one
  // of kapfix::link::Topics(); the handler gets the decoded message of that topic's type.
  void OnMessage(const std::string& topic, MessageHandler handler);
  // Every stream message as received, before decoding (subscribes to every topic).
  void OnRawMessage(RawHandler handler);
  // Called on each change of LinkStatus::up.
  void OnLinkChange(LinkHandler handler);

  // Connects both sockets and starts the I/O thread. Throws std::runtime_error for an
  // endpoint ZeroMQ refuses, or when already started. Connecting needs no agent: ZeroMQ keeps
  // trying in the background.
  void Start();
  // Joins the I/O thread; pending requests get std::nullopt. Idempotent.
  void Stop();

  // Sends `command` (its header is stamped here) and waits for the reply; std::nullopt when
  // none came within `timeout` (link down, agent gone, or the client not started).
  std::optional<kapfix::v1::Reply> Request(kapfix::v1::Command command,
                                           std::chrono::milliseconds timeout);
  // The same without blocking: `done` runs exactly once, on the I/O thread (or on the
  // caller's, when the client is not running), with the reply or std::nullopt.
  void RequestAsync(kapfix::v1::Command command, std::chrono::milliseconds timeout,
                    ReplyHandler done);

  // Waits until a message arrived on the stream socket, which proves that the subscriptions
  // are in place: the agent's periodic heartbeat arrives within one heartbeat interval.
  // Use it before commanding something whose results travel on the streams (ZeroMQ does not
  // deliver what a PUB sent before the subscription reached it). False on timeout.
  bool WaitForStreams(std::chrono::milliseconds timeout);

  LinkStatus Status() const;
  // [count] LinkStatus::sequence_gaps of one topic only, e.g. "telemetry" (tails included).
  std::uint64_t SequenceGaps(std::string_view topic) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kapfix::link
