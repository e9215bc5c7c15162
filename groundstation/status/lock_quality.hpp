#pragma once

// How good the lock is, from the telemetry alone (issue 14): LOCKED, DEGRADED or LOST, read
// from the agent's lock state, its confidence and the residual's RMS over the last few
// seconds. The residual is the displacement still left while fixating (current match minus
// reference, SPEC §1): what the servos have not yet taken out. Qt-free arithmetic, so the
// thresholds are tested without a window.

#include <cstdint>
#include <deque>
#include <string>

#include "kapfix/v1/telemetry.pb.h"

namespace kapfix::station {

enum class LockVerdict {
  kNone,      // the agent is not fixating or following: there is no lock to judge
  kLocked,    // trusted match, small residual
  kDegraded,  // low confidence or a residual the operator should watch
  kLost,      // the agent says so, or the residual is far beyond any useful photo
};

struct LockQualityOptions {
  double window_s = 5.0;             // [s] of capture time the RMS is taken over
  double confidence_window_s = 1.0;  // [s] the confidence is averaged over
  double degraded_confidence = 0.2;  // [0..1] mean confidence below this: DEGRADED
  double degraded_rms_px = 5.0;      // [px] RMS above this: DEGRADED
  double lost_rms_px = 20.0;         // [px] RMS above this: LOST

  bool IsValid(std::string* error) const;
};

struct LockReading {
  LockVerdict verdict = LockVerdict::kNone;
  double residual_px = 0;  // [px] |displacement| of the newest sample
  double rms_px = 0;       // [px] RMS of |displacement| over the window
  double confidence = 0;   // [0..1] mean over the confidence window
  // The agent says it does not hold the view this frame though the lock is not lost (issue
  // 9: a right match of a view the loop trails); the verdict is then at best degraded.
  bool off_target = false;
  // The loop's online calibration and forecast share while tracking (issue 9), e.g.
  // "deg/px 0.1050 ±3 % trusted · forecast 80 %"; empty when the controller keeps none.
  std::string calibration;
};

class LockQuality {
 public:
  explicit LockQuality(LockQualityOptions options = {});

  // Adds one telemetry sample and returns the reading it gives.
  const LockReading& add(const kapfix::v1::Telemetry& telemetry);
  const LockReading& reading() const { return reading_; }
  // Forgets every sample (a new session, a new lock).
  void reset();

 private:
  struct Sample {
    std::int64_t capture_us;  // [µs since epoch]
    double residual_sq;       // [px²]
    double confidence;        // [0..1]
  };

  LockQualityOptions options_;
  std::deque<Sample> samples_;
  double sum_sq_ = 0;  // [px²] over samples_
  kapfix::v1::Mode mode_ = kapfix::v1::MODE_UNSPECIFIED;
  LockReading reading_;
};

}  // namespace kapfix::station
