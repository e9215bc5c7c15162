// Writes a small session file for the Python reading check (session_file_python_test.py):
// five telemetry messages numbered 1…5 with frame numbers 10…14 and one log line "sample", each
// stamped as the agent stamps them, received at 1000 + sequence [µs].
//
// Usage: kapfix_session_sample_writer OUT
#include <exception>
#include <iostream>

#include "kapfix/v1/envelope_codec.hpp"
#include "kapfix/v1/log.pb.h"
#include "kapfix/v1/telemetry.pb.h"
#include "link/envelope.hpp"
#include "link/session_recorder.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: kapfix_session_sample_writer OUT\n";
    return 2;
  }
  try {
    kapfix::link::SessionRecorder recorder(argv[1]);
    constexpr int kTelemetryMessages = 5;
    for (int sequence = 1; sequence <= kTelemetryMessages; ++sequence) {
      kapfix::v1::Telemetry telemetry;
      kapfix::v1::Stamp(telemetry.mutable_header(), "sample-agent", sequence);
      telemetry.set_frame_number(9 + sequence);
      const kapfix::link::Envelope envelope = kapfix::link::Encode(telemetry);
      recorder.Write(envelope.topic, envelope.payload, 1000 + sequence);
    }
    kapfix::v1::Log log;
    kapfix::v1::Stamp(log.mutable_header(), "sample-agent", kTelemetryMessages + 1);
    log.set_text("sample");
    const kapfix::link::Envelope envelope = kapfix::link::Encode(log);
    recorder.Write(envelope.topic, envelope.payload, 1000 + kTelemetryMessages + 1);
    recorder.Flush();
  } catch (const std::exception& error) {
    std::cerr << "kapfix_session_sample_writer: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
