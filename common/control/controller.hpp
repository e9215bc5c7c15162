#pragma once

#include <limits>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "common/control/lens_calibration.hpp"

namespace kapfix {

struct ServoTargets {
  double pan_deg = 0.0;   // [deg]
  double tilt_deg = 0.0;  // [deg]
};

// What one frame tells the controller (SPEC §2.8).
struct ControlInput {
  // [px] measured displacement, stored-reference convention (SPEC §1): where the reference
  // patch is found minus where it was. An axis that was not searched carries 0.
  cv::Point2d displacement_px{0, 0};
  double confidence = 0.0;  // [0, 1] of the match
  bool found = false;       // false: no usable measurement this frame (the servos hold)
  double dt_s = 0.0;        // [s] since the previous Update; ≤ 0 or non-finite: no time passed
  // [deg/px] per axis, a calibration the caller found the frames to agree with (ServoBelief's
  // scale of the stored one, under latency jitter); 0: none. A controller that estimates its
  // own may act on it until its estimate is first trusted.
  double pan_deg_per_px_hint = 0.0;
  double tilt_deg_per_px_hint = 0.0;
  // [deg] Set while the lock is lost (FixationLoop): the centre of the swing seen while the
  // view was tracked (FixationLoop::swing_centre). With no measurement the servos head there
  // at the rate limit instead of holding, so that the swing carries the view about the
  // reference, where the widened search can find it again; held where a wrong match or a
  // forecast left them, the view stays off by that much for as long as the loss lasts
  // (baboon.jpg after SSP: 92 px RMS against the swing's own 38). None: hold.
  std::optional<ServoTargets> return_to;
};

// Operator-set gains (SPEC §2.8). The hard servo limits are enforced elsewhere (by the servo
// driver), never here: a controller may ask for anything.
struct ControllerGains {
  double p = 1.0;  // [1] share of the measured displacement corrected per frame
  double i = 0.0;  // [1/s] PID only: integral gain on ∫displacement dt
  double d = 0.0;  // [s] PID only: derivative gain on d(displacement)/dt
  // [px] per axis, measured displacements smaller than this are not corrected, so the
  // servos do not hunt on measurement noise.
  double dead_band_px = 0.5;
  // [deg/s] largest move of the commanded angle per second on each axis (CommandRateLimiter);
  // 0 = none.
  double rate_limit_deg_per_s = 0;
  // [px] PID only: the integral term's contribution is clamped to ± this (anti-windup).
  double integral_limit_px = 50;

  bool IsValid(std::string* error) const;

  // The dead band and the rate limit, applied here once for every kind of controller.
  // `displacement_px` where it is at least the dead band, else 0: what a controller corrects.
  double Correctable(double displacement_px) const;
  // [px] how far |displacement_px| reaches beyond the dead band; 0 inside it.
  double BeyondDeadBand(double displacement_px) const;
  // ApplyRateLimit at this rate limit, from `from` (CommandRateLimiter: the previous command).
  ServoTargets LimitRate(const ServoTargets& target, const ServoTargets& from, double dt_s) const;
  // The same gains without a rate limit (for a controller inside another that limits last).
  ControllerGains WithoutRateLimit() const;
  // The operator-set fields by the names of their settings (kapfix.v1.Gains), listed once so
  // that the agent copies its settings in by name: visit(name, field) for each.
  template <typename Visitor>
  void VisitFields(Visitor&& visit) {
    visit("p", p);
    visit("i", i);
    visit("d", d);
    visit("dead_band_px", dead_band_px);
    visit("rate_limit_deg_per_s", rate_limit_deg_per_s);
  }
};

// What a controller that learns in flight currently believes, read-only (issue 9: for
// telemetry, the flight report and the station).
struct ControlEstimate {
  struct Axis {
    // [deg/px] the online estimate of the lens's degrees per pixel (from the loop's commands
    // and the measured response); the stored calibration until the first fit.
    double deg_per_px = 0;
    // [1] relative standard deviation of that estimate, σ/estimate; +∞ before a fit.
    double relative_sigma = std::numeric_limits<double>::infinity();
    // Whether the estimate is trusted (only then does the controller act on it).
    bool trusted = false;
    // [0, 1] share of the swing forecast's feed-forward in this axis's target (0: plain P).
    double forecast_weight = 0;
  };
  Axis pan;
  Axis tilt;
  // [0, 1] one figure for both axes (Telemetry.forecast_weight): their mean.
  double forecast_weight() const { return 0.5 * (pan.forecast_weight + tilt.forecast_weight); }
};

// Turns one frame's measurement into servo targets. `current` is what the frame was seen
// through: the servo angles while it was exposed (in simulation the servos' output angles;
// on open-loop hardware the command that had taken effect by then). Working from the angles
// the measurement belongs to, rather than from the last command, keeps plain P stable at
// gain 1 whatever the servo latency: target = current + displacement · deg_per_px is exactly
// the angle that would have held that frame.
class Controller {
 public:
  virtual ~Controller() = default;
  virtual ServoTargets Update(const ControlInput& input, const ServoTargets& current) = 0;
  // Forgets all history (integrator, swing model): call on a new reference or lost lock.
  virtual void Reset() = 0;
  virtual std::string name() const = 0;
  // The lens's deg per px may change in flight (new calibration, another lens profile).
  virtual void SetCalibration(const LensCalibration& calibration) = 0;
  // New operator gains, bumpless: the history (swing models, integrator, previous error)
  // stays, so a gain change — or the same gains sent again — causes no transient (issue 15,
  // item 7). Throws std::invalid_argument for gains that are not IsValid (nothing changes).
  virtual void SetGains(const ControllerGains& gains) = 0;
  // The online calibration estimate and forecast weights; nothing for a controller that
  // does not learn in flight (P, PID).
  virtual std::optional<ControlEstimate> estimate() const { return std::nullopt; }
};

// Limits each axis's move from `current` to rate_deg_per_s · dt_s; rate 0 = no limit. A
// non-positive or non-finite dt with a rate set means no time passed: the targets stay at
// `current`.
ServoTargets ApplyRateLimit(const ServoTargets& target, const ServoTargets& current,
                            double rate_deg_per_s, double dt_s);

}  // namespace kapfix
