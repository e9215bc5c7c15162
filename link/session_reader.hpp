#pragma once

// Reads a file written by SessionRecorder (format in session_recorder.hpp), message by
// message, for replay and for tests.

#include <cstdint>
#include <fstream>
#include <optional>
#include <string>

namespace kapfix::link {

struct RecordedMessage {
  std::int64_t receive_time_us = 0;  // [µs since epoch, the recorder's clock]
  std::string topic;
  std::string payload;
};

class SessionReader {
 public:
  // Throws std::runtime_error when the file cannot be opened or does not start with the magic.
  explicit SessionReader(const std::string& path);

  // The next message; std::nullopt at the end, or when the file is cut short (error() then
  // says so: a recording interrupted mid-write keeps every complete message before the cut).
  std::optional<RecordedMessage> Next();

  const std::string& error() const { return error_; }

 private:
  std::string path_;
  std::ifstream in_;
  std::string error_;
};

}  // namespace kapfix::link
