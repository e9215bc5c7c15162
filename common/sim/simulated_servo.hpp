#pragma once

#include <cstdint>
#include <deque>
#include <string>

namespace kapfix {

struct SimulatedServoOptions {
  double min_deg = -45;  // [deg] hard limit
  double max_deg = 45;   // [deg] hard limit
  // [deg/frame] fastest shaft motion, the servo's rated speed. The loop's commands must stay
  // within it (EvaluateClosedLoop's driver; the agent's limiter, whose max_rate the agent's
  // simulation takes as this speed) or the servo lags what the loop believes it shows.
  double rate_limit_deg_per_frame = 3;
  double dead_band_deg = 0.05;  // [deg] position errors below this are not corrected
  double backlash_deg = 0.1;    // [deg] total play between shaft and output
  int latency_frames = 1;       // [frames] Steps before a command starts to act
  double initial_deg = 0;       // [deg] shaft and output at start, within the limits
  // [frames] latency jitter: when > latency_frames, each command's latency is drawn
  // uniformly from latency_frames…latency_max_frames (seeded); 0 = fixed latency.
  int latency_max_frames = 0;
  std::uint32_t seed = 1;  // of the latency jitter

  bool IsValid(std::string* error) const;
};

// A hobby servo for the closed-loop simulation (SPEC §3, §2.8).
//
// Command(target) is clamped to [min, max] and queued; it becomes the shaft's target after
// latency_frames Steps (latency 0: the very next Step moves towards it; latency 1: the next
// Step does not yet, the one after does). Commands keep their order; a later one replaces
// the target once its own delay has passed; with latency jitter a command overtaken by a
// newer one that became active first is dropped, as a servo only ever follows the newest
// pulse it has seen: the PWM line carries one pulse width at a time, refreshed every 20 ms,
// and the servo's electronics drive towards the width of the last pulse they measured — a
// command held up in the host (USB, scheduler) until its successor was written never
// appears on the line. The loop's belief (ServoBelief) assumes the same rule. NaN commands are
// ignored (the servo keeps its current target and commanded()), since a broken controller must not
// move the camera; ±∞ and absurd values are clamped like any other.
//
// Each Step the shaft moves towards the target by at most rate_limit; when it is within
// dead_band of the target it does not move at all. The output is coupled to the shaft
// through backlash: it stays put while the shaft moves inside the play and is dragged once
// the gap is taken up, so |shaft − output| ≤ backlash/2 and, after a reversal, the shaft
// travels the whole backlash before the output follows. Shaft and output never leave
// [min, max].
class SimulatedServo {
 public:
  // Throws std::invalid_argument for options that are not IsValid.
  explicit SimulatedServo(SimulatedServoOptions options);

  void Command(double target_deg);
  // Advances one frame; returns the output angle [deg].
  double Step();

  double angle() const { return output_; }         // [deg] output (what moves the camera)
  double shaft() const { return shaft_; }          // [deg] motor side of the backlash
  double commanded() const { return commanded_; }  // [deg] last accepted, clamped command
  const SimulatedServoOptions& options() const { return options_; }

 private:
  struct Pending {
    std::int64_t active_at_step;  // the Step (0-based) from which it is the target
    double target_deg;
    std::int64_t issued = 0;  // order of the command
  };
  int Latency() const;  // [frames] of the next command

  SimulatedServoOptions options_;
  std::deque<Pending> pending_;
  std::int64_t steps_ = 0;           // Steps done
  std::int64_t issued_ = 0;          // commands accepted
  std::int64_t active_issued_ = -1;  // order of the command that is the target now
  double target_;
  double shaft_;
  double output_;
  double commanded_;
};

}  // namespace kapfix
