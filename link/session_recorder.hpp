#pragma once

// Writes received link messages to a file, for `kapfix-ctl record` and the station's session
// recording; SessionReader reads them back. The bytes are the agent's, untouched, so a
// recording replays through the same decoder as the live link.
//
// File format (all integers little-endian):
//   magic   8 bytes "KFXREC01"
//   then per message:
//     u64 receive_time_us   [µs since epoch, the recorder's clock]
//     u32 topic_bytes,   topic   (e.g. "telemetry")
//     u32 payload_bytes, payload (the serialized kapfix.v1 message)

#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>

namespace kapfix::link {

inline constexpr std::string_view kSessionMagic = "KFXREC01";

class SessionRecorder {
 public:
  // Creates or truncates `path`; throws std::runtime_error when it cannot be opened.
  explicit SessionRecorder(const std::string& path);

  // Appends one message; throws std::runtime_error when the write fails (disk full).
  void Write(std::string_view topic, std::string_view payload, std::int64_t receive_time_us);
  void Flush();

  std::uint64_t messages() const { return messages_; }

 private:
  std::string path_;
  std::ofstream out_;
  std::uint64_t messages_ = 0;
};

}  // namespace kapfix::link
