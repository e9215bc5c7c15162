#pragma once

// The telemetry the graphs show, kept as numbers (bounded) so that the plots can be paused,
// rebuilt and exported to CSV exactly as measured. Time is the agent's capture time; each
// session has its own origin and number, and within a session time only goes forward. A new
// session starts when the agent restarts (startSession) and when its capture clock goes back
// (the simulated camera counts from 0 again), so samples of two clocks never interleave.

#include <QString>
#include <cstddef>
#include <cstdint>
#include <deque>

#include "kapfix/v1/telemetry.pb.h"

class QIODevice;

namespace kapfix::station {

struct TelemetrySample {
  int session = 1;              // [count] agent session the sample belongs to (1 = first)
  double time_s = 0;            // [s] since the session's first capture time
  std::int64_t capture_us = 0;  // [µs since epoch] the agent's capture time
  std::uint64_t frame = 0;      // [count] agent frame number
  double x_px = 0;              // [px] displacement, sub-pixel part included
  double y_px = 0;              // [px]
  double confidence = 0;        // [0..1]
  double distance = 0;          // [grey level²] SSD at the match
  double pan_target_deg = 0;    // [deg] commanded
  double tilt_target_deg = 0;   // [deg]
  double pan_deg = 0;           // [deg] reached
  double tilt_deg = 0;          // [deg]
};

class TelemetrySeries {
 public:
  // [count] oldest samples are dropped beyond this: 20 min at 30 fps.
  static constexpr std::size_t kDefaultCapacity = 36'000;

  explicit TelemetrySeries(std::size_t capacity = kDefaultCapacity) : capacity_(capacity) {}

  // Appends one sample; a capture time earlier than the session's newest starts a new session.
  const TelemetrySample& append(const kapfix::v1::Telemetry& telemetry);
  // The following samples belong to a new session, with their own time origin.
  void startSession();
  int session() const { return session_; }
  // [count] sessions started because the capture time went back.
  std::uint64_t clockRestarts() const { return clock_restarts_; }
  void clear();

  const std::deque<TelemetrySample>& samples() const { return samples_; }
  // [count] samples ever appended (also those dropped), so a view knows what it has not drawn.
  std::uint64_t appended() const { return appended_; }

  // One header line, then one line per sample; columns named with their units.
  void writeCsv(QIODevice& out) const;

 private:
  std::size_t capacity_;
  std::deque<TelemetrySample> samples_;
  int session_ = 1;
  bool session_empty_ = true;
  std::int64_t origin_us_ = 0;  // [µs since epoch] capture time of the session's first sample
  std::int64_t newest_us_ = 0;  // [µs since epoch] capture time of the session's newest sample
  std::uint64_t appended_ = 0;
  std::uint64_t clock_restarts_ = 0;
};

}  // namespace kapfix::station
