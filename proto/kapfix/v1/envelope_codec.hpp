#pragma once

// Decoding and stamping of kapfix.v1 messages, independent of ZeroMQ: decoding checks size,
// well-formedness and protocol version before anything reads a field. Topics, and which type
// travels under which, are the link's (link/topic_names.hpp, link/topic_table.hpp,
// link/envelope.hpp).

#include <google/protobuf/message.h>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/header.pb.h"
#include "kapfix/v1/version.hpp"

namespace kapfix::v1 {

// Receive size limits [bytes]. Streams: a full-resolution photo travels in chunks of
// kPhotoChunkBytes, so 4 MiB leaves room for a large JPEG video frame. Commands are small; a
// command socket should refuse anything larger than kMaxCommandBytes (ZMQ_MAXMSGSIZE).
inline constexpr std::size_t kMaxMessageBytes = std::size_t{4} << 20U;   // [bytes]
inline constexpr std::size_t kMaxCommandBytes = std::size_t{64} << 10U;  // [bytes]
inline constexpr std::size_t kPhotoChunkBytes = std::size_t{1} << 20U;   // [bytes]

// Parses `bytes` into `out` (cleared first) and checks it is fit to use: at most max_bytes
// long, well-formed, carrying a Header at field 1 whose protocol_version is kProtocolVersion.
// On failure returns false, leaves `out` cleared, and sets `error` to a sentence naming the
// problem and `code` (both optional) to what a Reply should carry.
bool Decode(std::string_view bytes, google::protobuf::Message* out, std::size_t max_bytes,
            std::string* error, ErrorCode* code = nullptr);

// `bytes` as text for an error message: printable ASCII kept, anything else as \xNN, at most
// 48 characters (routing ids are binary, keys may be long).
std::string Printable(std::string_view bytes);

// libprotobuf logs every invalid UTF-8 string it parses to stderr, unthrottled, so a peer
// could flood the log with them; Decode() already refuses such a message as malformed with a
// reason. This replaces libprotobuf's log handler with one that drops its lines below FATAL
// and counts them (LibprotobufLinesDropped). Call once at start, before any thread decodes.
void QuietLibprotobufLog();
std::uint64_t LibprotobufLinesDropped();

// Now [µs since the Unix epoch] (system clock).
std::int64_t NowMicros();

// Fills a header for sending: protocol version, agent id, sequence, send time = now, and
// capture time = now unless it is already set (a frame's capture time is kept), and the
// sender's boot id (0 = unset: a station).
void Stamp(Header* header, const std::string& agent_id, std::uint64_t sequence,
           std::uint64_t boot_id = 0);

// Refuses replayed and stale messages: per sender, every accepted sequence number must be
// greater than the last one accepted from that sender. Sequence 0 (unset) is refused.
// The sender key is whatever identifies a peer reliably — the CURVE public key or ZeroMQ
// routing id of a station, the agent id for an agent's streams — not a field the peer could
// set at will. Memory is bounded: beyond max_senders, the sender heard from least recently
// is forgotten. Call Forget() when a sender's connection ends if its numbering restarts.
// Not thread-safe: one owner (the thread that reads the socket).
class SequenceGuard {
 public:
  explicit SequenceGuard(std::size_t max_senders = 256);

  // True and remembers `sequence` if it is newer than the last one accepted from `sender`;
  // false with a reason in `error` (optional) otherwise.
  bool Accept(std::string_view sender, std::uint64_t sequence, std::string* error);

  // Forgets a sender: its next message starts a new numbering.
  void Forget(std::string_view sender);

  // The last sequence accepted from `sender`, if any.
  std::optional<std::uint64_t> LastAccepted(std::string_view sender) const;

  std::size_t sender_count() const { return senders_.size(); }

 private:
  struct Entry {
    std::uint64_t last_sequence = 0;
    std::uint64_t last_use = 0;  // value of use_clock_ when last accepted
  };
  void EvictLeastRecentlyUsed();

  std::size_t max_senders_;
  std::uint64_t use_clock_ = 0;
  std::unordered_map<std::string, Entry> senders_;
};

}  // namespace kapfix::v1
