#pragma once

// Reads the session files kapfix wrote before the length-delimited protobuf format (issue 11):
// the hand-made KFXREC01 framing. SessionReader hands such a file to it, so old recordings
// still replay; nothing writes this format any more.
//
// Layout (all integers little-endian):
//   magic   8 bytes "KFXREC01"
//   then per message:
//     u64 receive_time_us   [µs since epoch, the recorder's clock]
//     u32 topic_bytes,   topic   (e.g. "telemetry")
//     u32 payload_bytes, payload (the serialized kapfix.v1 message)

#include <fstream>
#include <optional>
#include <string>
#include <string_view>

#include "link/recorded_message.hpp"

namespace kapfix::link {

inline constexpr std::string_view kLegacySessionMagic = "KFXREC01";

class LegacySessionReader {
 public:
  // Throws std::runtime_error when the file cannot be opened or does not start with the magic.
  explicit LegacySessionReader(const std::string& path);

  // The next message; std::nullopt at the end, or when the file is cut short or holds a
  // corrupted length (error() then says so and names the byte offset: a recording interrupted
  // mid-write keeps every complete message before the cut).
  std::optional<RecordedMessage> Next();

  const std::string& error() const { return error_; }

 private:
  std::string path_;
  std::ifstream in_;
  std::string error_;
};

}  // namespace kapfix::link
