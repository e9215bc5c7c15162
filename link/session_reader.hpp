#pragma once

// Reads a session file back, message by message, for replay and for tests: the
// length-delimited kapfix.v1.SessionRecord format SessionRecorder writes (session_recorder.hpp)
// and, through LegacySessionReader, the KFXREC01 files written before it, so old recordings
// still replay.

#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include "link/recorded_message.hpp"

namespace google::protobuf::io {
class FileInputStream;
}  // namespace google::protobuf::io

namespace kapfix::link {

class LegacySessionReader;

class SessionReader {
 public:
  // Throws std::runtime_error with a one-line reason when the file cannot be opened, is not a
  // session recording in either format, or is of a newer version than this build reads.
  explicit SessionReader(const std::string& path);
  ~SessionReader();
  SessionReader(const SessionReader&) = delete;
  SessionReader& operator=(const SessionReader&) = delete;

  // The next message; std::nullopt at the end, or when the file is cut short or corrupted
  // (error() then says so, naming the byte offset of the record: a recording interrupted
  // mid-write keeps every complete message before the cut).
  std::optional<RecordedMessage> Next();

  const std::string& error() const { return error_; }

  // "kapfix-session 1", or "KFXREC01" for an old recording.
  const std::string& format() const { return format_; }

 private:
  void ReadFormatRecord();
  std::optional<RecordedMessage> NextLegacy();

  std::string path_;
  std::string format_;
  std::string error_;
  std::unique_ptr<LegacySessionReader> legacy_;
  std::unique_ptr<google::protobuf::io::FileInputStream> in_;
};

}  // namespace kapfix::link
