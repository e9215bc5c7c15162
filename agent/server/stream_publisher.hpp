#pragma once

// The agent's streams (SPEC §4, §5): a PUB socket on its own thread, fed from any thread
// through a queue, so the control loop never waits for the network. Publish() stamps nothing
// itself: the publisher thread stamps each message (agent id, per-topic sequence, send time;
// a capture time already set is kept) just before handing it to ZeroMQ, so sequence numbers
// count what went on the wire and a gap seen by a station is a loss on the link. What never
// reached the wire is counted here instead, for Telemetry.telemetry_dropped and
// video_frames_dropped.
//
// - Video ("video"): only the latest frame waits; a newer one replaces it (counted as a
//   stale drop), and at most one is sent per video_min_interval.
// - Everything else: a FIFO bounded in messages and bytes. A full queue refuses the new
//   message and counts it.
// - Per-subscriber isolation (issue 15): each subscriber has its own ZeroMQ queue of
//   send_high_water_mark messages; a subscriber that does not read loses its own messages once
//   its queue is full, never anyone else's (no XPUB_NODROP). It is told by the gap in each
//   topic's header.sequence, and of the tail of a burst by the periodic Heartbeat's
//   newest_sequence (the newest sequence sent on each topic). libzmq does not report which
//   subscriber dropped, so each subscriber counts its own losses (link::StreamLossCounter) and
//   reports them in its heartbeats to the command server (SubscriberLossBook).
// - What a subscriber sends is bounded: ZMQ_MAXMSGSIZE of max_subscription_bytes (a
//   subscription is a message to the publisher; libzmq builds one trie node per byte of it),
//   and a peer that does not finish its handshake within handshake_timeout is dropped. The
//   socket is an XPUB in ZMQ_XPUB_MANUAL mode: each subscription reaches the publisher thread,
//   which applies it only when the SubscriptionBook admits it (distinct subscriptions per peer
//   and their length bounded) and ends the connection of a peer that goes beyond (libzmq
//   keeps what it read in the connection's trie until then); behind an intake, each is
//   reported consumed.
// - A Heartbeat is published every heartbeat_interval, naming the newest sequence sent on
//   every other topic (Heartbeat.newest_sequence).

#include <google/protobuf/message.h>

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "agent/server/stream_sink.hpp"
#include "agent/server/subscription_book.hpp"
#include "link/bounded_intake.hpp"
#include "link/curve_server_keys.hpp"

namespace kapfix::agent {

struct StreamPublisherOptions {
  // ZeroMQ endpoint to bind; "tcp://127.0.0.1:*" binds an ephemeral port (see Start()).
  std::string bind_endpoint = "tcp://*:5556";
  std::string agent_id = "kapfix-agent";
  std::uint64_t boot_id = 0;                         // header.boot_id of every message (DrawBootId)
  std::size_t queue_messages = 4096;                 // [count] non-video messages waiting, at most
  std::size_t queue_bytes = std::size_t{64} << 20U;  // [bytes] and their serialized size
  std::chrono::milliseconds heartbeat_interval{1000};
  std::chrono::microseconds video_min_interval{0};  // [µs] 1 / largest video frame rate
  int send_high_water_mark = 1000;                  // [messages] per subscriber, inside ZeroMQ
  // [bytes] ZMQ_MAXMSGSIZE, the longest message a subscriber may send: a larger one drops its
  // connection before anything is allocated for it. It bounds a subscription (topics are at
  // most a dozen characters) and must leave room for the CurveZMQ handshake's commands (the
  // largest, INITIATE, is a few hundred bytes), to which libzmq applies the same limit.
  std::int64_t max_subscription_bytes = 1024;
  // [ms] ZMQ_HANDSHAKE_IVL: a connection that has not completed its ZMTP (and CurveZMQ)
  // handshake within this is closed, so silent connections cannot hold file descriptors.
  std::chrono::milliseconds handshake_timeout{2000};
  // [ms] ZeroMQ heartbeats (ZMTP PING): a subscriber that vanished without closing its TCP
  // connection is dropped, and its queue freed. The timeout is long because a subscriber
  // answers a PING only once it has read everything queued before it: a slow but live
  // station behind a backlog must not be cut off.
  std::chrono::milliseconds zmtp_heartbeat_interval{1000};
  std::chrono::milliseconds zmtp_heartbeat_timeout{10000};
  // [count] connections at once; one accepted beyond this is closed at once (keep it under
  // the open-file limit, with room for the agent's own files).
  std::size_t max_connections = 4096;
  // CurveZMQ: encrypt every connection and let only the listed stations subscribe. Unset:
  // plain.
  std::optional<kapfix::link::CurveServerKeys> curve;
  SubscriptionBookOptions subscriptions;
  // Issue 15: as CommandServerOptions::intake. A subscriber sends little (subscriptions of at
  // most max_subscription_bytes), so its budget is small.
  std::optional<link::BoundedIntakeOptions> intake =
      link::IntakeWithBudget(std::uint64_t{64} * 1024);
};

class StreamPublisher : public StreamSink {
 public:
  struct Counters {
    std::uint64_t telemetry_sent = 0;          // [count] "telemetry" messages handed to ZeroMQ
    std::uint64_t telemetry_dropped = 0;       // [count] refused: queue full
    std::uint64_t video_sent = 0;              // [count]
    std::uint64_t video_dropped = 0;           // [count] replaced by a newer frame before sending,
                                               // or refused by ZeroMQ's high-water mark
    std::uint64_t other_sent = 0;              // [count] every other topic
    std::uint64_t other_dropped = 0;           // [count] refused: queue full
    std::uint64_t heartbeats_sent = 0;         // [count]
    std::uint64_t rejected = 0;                // [count] not a link message (no topic or header)
    std::uint64_t subscriptions_admitted = 0;  // [count] applied
    std::uint64_t subscriptions_refused = 0;   // [count] over SubscriptionBookOptions' bounds
    std::uint64_t intake_paused = 0;           // [count] times a peer reached its byte budget
    std::uint64_t intake_closed = 0;           // [count] peers closed for staying at it
  };

  explicit StreamPublisher(StreamPublisherOptions options = {});
  ~StreamPublisher() override;  // Stop()s
  StreamPublisher(const StreamPublisher&) = delete;
  StreamPublisher& operator=(const StreamPublisher&) = delete;

  // Starts the thread, binds, and returns the bound endpoint (ZMQ_LAST_ENDPOINT). Throws
  // std::runtime_error when binding fails or when already started.
  std::string Start();
  // Returns within about a millisecond; idempotent. What is still queued is discarded.
  void Stop();

  // Queues a copy of `message` (any type with a topic, e.g. Telemetry, VideoFrame, SliceReport,
  // Photo, Log, AgentState). Thread-safe, never blocks on the network. False when the message
  // was dropped or rejected, which the counters record. Messages queued before Start() wait.
  bool Publish(const google::protobuf::Message& message) override;

  // Thread-safe: e.g. when a station changes VideoSettings.fps.
  void SetVideoMinInterval(std::chrono::microseconds interval);

  Counters counters() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace kapfix::agent
