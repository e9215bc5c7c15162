#pragma once

#include <cstddef>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "agent/pipeline/pipeline.hpp"
#include "agent/pipeline/telemetry_recorder.hpp"
#include "kapfix/v1/photo.pb.h"

namespace kapfix::agent {

// The closed-loop figures of one flight (issue 3). The error and lock figures are over the
// frames spent fixating, each against the view of the reference frame it held (which itself is
// left out, 0 px by construction); latency over every frame after the first.
struct FlightFigures {
  double rms_error_px = 0;   // [px] RMS of |view offset| (simulation truth); NaN without truth
  double lock_lost_pct = 0;  // [%] fixating frames reported lock lost
  double p95_error_px = 0;   // [px] 95th percentile of the true view error; NaN without truth
  // [%] fixating frames with a true view error > 10 px, and of those the ones where the loop
  // claimed to hold the view (off_target false: lock held, match trusted, measured within the
  // off-target distance), as shares of all fixating frames with truth; NaN without truth.
  double gross_pct = 0;
  double silent_gross_pct = 0;
  // [%] the gross frames with lock_lost false alone, whether or not the loop said it was off
  // target (the first reading of silent), and the frames it said it was off target.
  double gross_lock_held_pct = 0;
  double off_target_pct = 0;
  std::uint64_t frames = 0;        // control steps, reference frame included
  double fps = 0;                  // frames processed per wall-clock second
  double loop_latency_p50_ms = 0;  // [ms]
  double loop_latency_p99_ms = 0;  // [ms]
  double rss_mb = 0;               // [MB] peak resident set (VmHWM), 0 when unknown
  // [1] the controller's online deg/px estimate at the flight's end (its last fixating frame)
  // ÷ the true value, per axis (1 = perfect), with its relative standard deviation and
  // whether the controller acted on it. NaN when there is nothing to compare: then
  // deg_per_px_estimate_missing says why (no truth outside simulation, a controller without
  // an online estimate, no fixating frame).
  double deg_per_px_estimate_ratio = std::numeric_limits<double>::quiet_NaN();
  double deg_per_px_estimate_ratio_tilt = std::numeric_limits<double>::quiet_NaN();
  double deg_per_px_estimate_sigma = std::numeric_limits<double>::quiet_NaN();
  bool deg_per_px_estimate_trusted = false;
  std::string deg_per_px_estimate_missing;
};

// The photo figures of a flight (issue 13's benchmark), means over `photos`; NaN for none.
struct PhotoFigures {
  std::size_t photos = 0;
  double view_speed_px_mean = 0;  // [px/frame] residual view speed at capture
  double view_blur_px_mean = 0;   // [px] view travel during the exposure
  double offset_px_mean = 0;      // [px] residual offset at capture
  double sharpness_mean = 0;      // [grey²] variance of the Laplacian, whole photo
  double wait_s_mean = 0;         // [s] request → capture
  double lock_lost_share = 0;     // [1] photos taken with the lock not trusted
};
PhotoFigures ComputePhotoFigures(const std::vector<kapfix::v1::PhotoMetadata>& photos);

// What the summary says about the flight besides its figures.
struct FlightDescription {
  std::string controller;  // the controller's word: "p", "pid", "predictive"
  std::string shutter;     // the shutter's word: "interval", "best-phase"
  bool simulated = false;
  std::string world;   // the simulated world (WorldOptions::Describe); "none" outside simulation
  std::string scene;   // the simulated scene photo; empty outside simulation
  std::string motion;  // "kite", "boat"; "none" outside simulation
};

// The flight's summary (kapfix-agent --report prints it and writes it as DIR/summary.json):
// each figure under its key, NaN as null. Scripts and tests read these keys (deploy/fly-sim.sh,
// bench/, tests/integration): add keys, rename none.
nlohmann::json FlightSummary(const FlightFigures& figures, const PhotoFigures& photos,
                             const PipelineStats& stats, const FlightDescription& flight);

// `true_deg_per_px` [deg/px]: the lens's true degrees per pixel, known in simulation only.
FlightFigures ComputeFlightFigures(const std::vector<TelemetryRecord>& records,
                                   const PipelineStats& stats,
                                   std::optional<double> true_deg_per_px = std::nullopt);

// [MB] VmHWM of /proc/self/status; 0 when it cannot be read.
double PeakRssMb();

// Writes DIR/summary.json (`summary`), DIR/telemetry.csv and DIR/displacement.png, each to a
// temporary file renamed into place. Creates DIR. Throws std::runtime_error naming the file.
void WriteFlightReport(const std::string& dir, const nlohmann::json& summary,
                       const std::vector<TelemetryRecord>& records);

}  // namespace kapfix::agent
