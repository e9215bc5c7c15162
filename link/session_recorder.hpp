#pragma once

// Writes received link messages to a file, for `kapfix-ctl record` and the station's session
// recording; SessionReader reads them back. The bytes are the agent's, untouched, so a
// recording replays through the same decoder as the live link.
//
// File format: length-delimited kapfix.v1.SessionRecord messages (proto/kapfix/v1/
// session.proto; protobuf's delimited format: a varint size, then the record), readable by any
// protobuf client. The first record is a SessionFormat {name "kapfix-session", version 1},
// every later one a RecordedMessage {receive time [µs], topic, payload}.

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace google::protobuf::io {
class FileOutputStream;
}  // namespace google::protobuf::io

namespace kapfix::v1 {
class SessionRecord;
}  // namespace kapfix::v1

namespace kapfix::link {

inline constexpr std::string_view kSessionFormatName = "kapfix-session";
inline constexpr std::uint32_t kSessionFormatVersion = 1;

class SessionRecorder {
 public:
  // Creates or truncates `path` and writes the format record; throws std::runtime_error when
  // it cannot be created.
  explicit SessionRecorder(const std::string& path);
  ~SessionRecorder();  // flushes what is buffered and closes the file
  SessionRecorder(const SessionRecorder&) = delete;
  SessionRecorder& operator=(const SessionRecorder&) = delete;

  // Appends one message; throws std::runtime_error when the write fails (disk full). Writes are
  // buffered: a failure may surface on a later Write or on Flush.
  void Write(std::string_view topic, std::string_view payload, std::int64_t receive_time_us);
  void Flush();

  std::uint64_t messages() const { return messages_; }

 private:
  void Append(const kapfix::v1::SessionRecord& record);

  std::string path_;
  std::unique_ptr<google::protobuf::io::FileOutputStream> out_;
  std::uint64_t messages_ = 0;
};

}  // namespace kapfix::link
