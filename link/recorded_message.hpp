#pragma once

// One link message as a recording holds it (SessionRecorder writes it, SessionReader and
// LegacySessionReader give it back): its topic and bytes as they came off the link.

#include <cstdint>
#include <string>

namespace kapfix::link {

struct RecordedMessage {
  std::int64_t receive_time_us = 0;  // [µs since epoch, the recorder's clock]
  std::string topic;                 // e.g. "telemetry"
  std::string payload;               // the serialized kapfix.v1 message
};

}  // namespace kapfix::link
