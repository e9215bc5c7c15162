#pragma once

// What a subscriber has lost of the agent's streams, per topic, counted in one place
// (issue 15: "a subscriber that does not read loses its own messages, counted, and it is
// told"). The agent numbers each topic's messages as it hands them to ZeroMQ
// (header.sequence), and its stream socket drops a whole message for a subscriber whose queue
// is full, without telling either side. The subscriber therefore counts:
// - gaps: a message whose sequence is beyond the last one received plus one;
// - tails: the agent's periodic Heartbeat names the newest sequence published on each topic
//   (newest_sequence); one beyond the last received is lost, even when no later message on
//   that topic ever comes to show the gap (the end of a burst).
//
// Why a heartbeat's newest_sequence can be trusted as "already arrived or lost" (and not "still
// in flight"): the agent's publisher thread stamps the heartbeat after its send of every
// message it names has returned, and libzmq's XPUB (lossy, no XPUB_NODROP) decides inside that
// send, in the caller's thread, for each subscriber's pipe: written whole (the high-water mark
// counts whole messages) or dropped. A subscriber's pipe, its TCP connection (and the intake's
// relay of it, which forwards bytes in order) and the SUB socket's own pipe are FIFO, and the
// SUB side never drops (a full SUB pipe stops reading TCP); a reconnection keeps the SUB's
// pipe, and what the agent had queued for the old connection is simply gone. So when the
// heartbeat is read, every message it names has been read before it or will never come.
//
// Not counted: what was published before this subscriber's first message on a topic (it
// cannot be told from what was published before its subscription took effect), and what it
// lost while it read nothing at all (it learns of it once it reads again). A message from an
// agent with another boot_id, or with a sequence not above the last, starts the topic over
// (a restarted agent numbers from 1).
//
// Not thread-safe: AgentLinkClient keeps one under its status lock.

#include <google/protobuf/message.h>

#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "kapfix/v1/header.pb.h"
#include "kapfix/v1/heartbeat.pb.h"

namespace kapfix::link {

class StreamLossCounter {
 public:
  // A stream message of `topic` with this header arrived. Returns the messages it shows lost
  // (its gap), 0 when none.
  std::uint64_t Received(std::string_view topic, const kapfix::v1::Header& header);
  // The agent's periodic heartbeat arrived (after Received() for it, on its own topic).
  // Returns the messages it shows lost at the tails of the topics already received.
  std::uint64_t Heard(const kapfix::v1::Heartbeat& heartbeat);

  // [count] lost on `topic` since the first message of it received; 0 for an unknown topic.
  std::uint64_t Lost(std::string_view topic) const;
  // [count] over every topic.
  std::uint64_t total() const { return total_; }
  // [count] per topic, for the heartbeat this station sends (Heartbeat.lost).
  void FillLost(kapfix::v1::Heartbeat* heartbeat) const;

 private:
  struct Topic {
    std::uint64_t last = 0;     // newest sequence received or counted lost; 0 = none yet
    std::uint64_t boot_id = 0;  // header.boot_id it was numbered under
    std::uint64_t lost = 0;     // [count]
  };
  std::map<std::string, Topic, std::less<>> topics_;
  std::uint64_t total_ = 0;
};

}  // namespace kapfix::link
