#pragma once

#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "agent/pipeline/step_observer.hpp"
#include "agent/pipeline/telemetry_record.hpp"

namespace kapfix::agent {

// Keeps every record for the flight report (`kapfix-agent --report`) until the run ends;
// thread-safe. A flight of 30 s at 30 frames/s is 900 records of ~130 bytes. Not wired in an
// agent that runs without --report, whose memory must stay bounded.
class TelemetryRecorder : public StepObserver {
 public:
  void Add(const TelemetryRecord& record);
  void OnStep(const CapturedFrame& frame, const FrameOutcome& outcome,
              const TelemetryRecord& record) override;
  std::vector<TelemetryRecord> records() const;
  std::size_t size() const;
  // CSV with a header row; empty cells for absent view offsets.
  static std::string ToCsv(const std::vector<TelemetryRecord>& records);

 private:
  mutable std::mutex mutex_;
  std::vector<TelemetryRecord> records_;
};

}  // namespace kapfix::agent
