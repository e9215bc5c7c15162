#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <limits>
#include <string>
#include <vector>

#include "common/control/controller.hpp"
#include "common/control/lens_calibration.hpp"

namespace kapfix {

// [deg] a servo with more play than this is broken (ServoBeliefOptions::play_deg).
inline constexpr double kMaxServoPlayDeg = 10;

struct ServoBeliefOptions {
  // [frames] from the capture of a frame to the first frame that shows the command sent for
  // it: 1 + the servo's latency, at its shortest and its longest (equal: a fixed latency).
  int min_delay_frames = 2;
  int max_delay_frames = 2;
  ServoTargets initial;  // [deg] what the servos show before the first command (park)
  // [deg/frame] per axis, the servo's top speed (its rated deg/s × the frame period): the
  // output moves at most this far a frame towards the command in effect, so a command the
  // latency jitter lets overtake another is reached over several frames. +∞: every command
  // is reached within the frame.
  ServoTargets max_step_deg{std::numeric_limits<double>::infinity(),
                            std::numeric_limits<double>::infinity()};
  // [deg] per axis, the servo's play (backlash) between its shaft and its output: the output
  // stays put while the shaft turns inside the play and is dragged along once it is taken
  // up, so after a move it trails the shaft by half the play. 0: none.
  ServoTargets play_deg{0, 0};

  bool IsValid(std::string* error) const;
};

// [1] When each command's latency is drawn uniformly from spread + 1 consecutive values, the
// share of frames whose command in effect was sent min_delay + k frames before (k = 0…spread):
// the servo follows the newest pulse that has reached it, so a short delay is more likely
// than a long one beyond the first (spread 1: ½, ½; spread 3: 0.25, 0.375, 0.28, 0.09).
// P(k or less) = 1 − Π_{i=0…k} (spread − i) / (spread + 1).
std::vector<double> DelayShares(int spread);

// What the loop believes the servos showed while a frame was exposed. A hobby servo cannot
// report its angle, so the belief is built from the commands the loop sent.
//
// With a fixed latency that is exact: the command sent min_delay_frames before. When the
// latency jitters, any command sent min…max_delay_frames before may be the one in effect —
// the servo follows the newest pulse that has reached it, so a slow command is overtaken and
// the servo never goes back to an older one. Consecutive commands differ by the swing's
// motion over a frame (up to ~16 px at SPEC §3's swing), so acting on their mean feeds an
// error of half that, with a random sign, into the controller's reconstruction of the swing
// (u = angle / deg_per_px + displacement): measured, it cost the predictive controller 25 px
// RMS where the true angle leaves 6.7 (aero1, 500 frames, latency 1…2 frames).
//
// Resolve therefore asks the frame itself: per axis, the candidate whose u continues the
// recent u (a line or parabola through the last resolved frames) is the command in effect.
// The swing is smooth over a frame while the candidates differ by its whole per-frame motion,
// so the choice is right whenever it matters; when the candidates nearly agree a wrong choice
// costs little. A frame alone cannot always tell: while commands arrive late several frames
// in a row, the views built on "on time" are as smooth, shifted by the servo's own step, and
// only the frame where the latency changes shows a kink in one of them. So the belief keeps a
// few hypotheses — which command was in effect at each recent frame, each with its own views —
// scored by how well each frame continued its views, and believes the best one; a frame that
// tells them apart re-ranks them, and the views after it are extrapolated from the right
// past. Deciding each frame alone, with views blended between the candidates where unsure (a
// view no command produced), let the extrapolation follow its own error. Realistic world,
// aero1, frames 40–150, the pan servo missed by (RMS): seed 3 in the agent's loop 2.3 px,
// with hypotheses 0.9; in EvaluateClosedLoop's default loop, seeds 3, 4, 5: 8.8, 8.0, 13.3 px
// (the loop acting on the wrong angles), with hypotheses 0.7, 0.5, 1.3. Without a
// measurement (or a history to extrapolate) the belief is the candidates' mean, weighted by
// how often each delay is the one in effect (DelayShares).
//
// A servo turns at a bounded speed (max_step_deg): while the latency jitters, the command in
// effect may jump by two frames' worth of commands, more than the servo turns in a frame, and
// the angle shown is then on the way to it, not at it. Each hypothesis therefore moves its
// own last angle towards the candidate by at most the servo's step. Taken as at the command,
// the lock-on's early frames (commands 3 deg/frame apart, servo 4 deg/frame) were believed up
// to 2 deg off, and the swing model fitted to those views overshot the first turn by 15 px.
//
// The views are smooth only with the true deg per px: with a calibration F × off, u keeps
// (1 − 1/F) of the servo's own motion, whose random early/late steps roughen the views until
// the frame cannot tell the candidates apart (realistic world, calibration ×1.3: 9.5–14 px
// RMS against 5.6–7.4 with the true deg/px in the belief). So each axis also scores a grid
// of scales of the given calibration (×0.5…2) by how well the resolved views continue under
// each, and reconstructs its views with the best one once it is clearly better than the
// given calibration (scale()). Both axes see through one lens: an axis whose views tell the
// scales apart far less well (a small, noisy swing) takes the other axis's.
class ServoBelief {
 public:
  // Throws std::invalid_argument for options that are not IsValid.
  explicit ServoBelief(ServoBeliefOptions options);

  // The command sent after processing `frame` (as the servos were given it: clamped and
  // rate-limited). Frames must not go backwards.
  void Sent(std::int64_t frame, const ServoTargets& command);
  // The frame about to be processed; returns the expected angles it was seen through (the
  // mean of the commands that may be in effect, weighted by DelayShares).
  ServoTargets Expose(std::int64_t frame);
  // The angles the exposed frame was seen through, given its measurement and the
  // calibration the controller reconstructs the swing with; remembers the choice.
  ServoTargets Resolve(const ControlInput& input, const LensCalibration& calibration);
  // Forgets the views (a new reference: displacements are measured against another frame).
  void ForgetViews();
  // The command that brings the servos' outputs (the camera) to `output_target` [deg]: a
  // shaft drags its output through the play, so it is sent half the play beyond the target
  // on the side the output must move to from where it is believed; a target at the believed
  // output leaves the shaft where it is believed. Without play, the target itself.
  ServoTargets ShaftCommand(const ServoTargets& output_target) const;

  // [deg] the belief for the exposed frame: Resolve's choice once it ran, else Expose's mean.
  const ServoTargets& Believed() const { return believed_; }
  // The commands that may be in effect for the exposed frame, per axis [deg] (diagnostics).
  std::vector<double> Candidates(int axis) const;
  // [1] per axis, the scale of the given calibration's px per deg that the views are
  // reconstructed with (1 until another scale continues the views clearly better).
  double scale(int axis) const;
  // [deg/px] `calibration` divided by scale() per axis: the calibration the views agree with.
  LensCalibration Scaled(const LensCalibration& calibration) const;

 private:
  struct Command {
    std::int64_t frame;  // sent after processing this frame
    std::int64_t order;  // sequence number
    ServoTargets targets;
  };
  struct Candidate {
    std::int64_t order;  // -1: the initial angles
    double deg;
    double prior;  // [1] DelayShares of the delays it stands for
  };
  // A resolved frame; its view u = deg · px_per_deg + displacement [px] (the swing, free of
  // the loop) depends on the scale it is reconstructed with.
  struct View {
    std::int64_t frame;
    double deg;              // [deg] the resolved angle (the output's)
    double displacement_px;  // [px]
    double shaft_deg;        // [deg] the servo's shaft behind that output (see play_deg)
  };
  // Where a servo stands: its output and the shaft that drags it.
  struct Pose {
    double output_deg;
    double shaft_deg;
  };
  // One hypothesis of which command was in effect at each recent frame.
  struct Path {
    std::deque<View> views;       // the last views under it, newest last
    std::int64_t in_effect = -1;  // order of the newest command in effect under it
    double cost = 0;  // [1] −log of its likelihood, less the best path's (0 for the best)
  };
  struct Axis {
    // For the exposed frame: every command a delay may have in effect.
    std::vector<Candidate> candidates;
    std::vector<Path> paths = {Path{}};  // the hypotheses kept, best first; never empty
    double miss_sq = 0;                  // [px²] EMA of the best path's squared miss
    std::vector<double> scale_miss_sq;   // [px²] per scale of the grid: EMA of the views' miss
    int scored = 0;                      // frames the scales were scored on
    std::size_t scale = 0;               // index of the scale in use (the grid's 1 at first)
  };

  void FillCandidates(int axis);
  double Expected(int axis) const;
  // [px] the swing's view at the exposed frame, the views taken at px_per_deg.
  double Predict(const std::deque<View>& views, double px_per_deg) const;
  // Every path extended by each candidate it allows; the best few kept (Axis::paths).
  void ExtendPaths(Axis* a, int axis, double displacement_px, double px_per_deg) const;
  // Where the servo stands at the exposed frame with `command_deg` in effect: its shaft turns
  // at most max_step_deg a frame from the newest of `views` and drags the output through the
  // play (the command itself, shaft and output, without a view).
  Pose Reached(const std::deque<View>& views, double max_step_deg, double play_deg,
               double command_deg) const;
  double ResolveAxis(int axis, double displacement_px, double deg_per_px);
  // Scores each scale on the newest view.
  void ScoreScales(Axis* a, double px_per_deg);
  // [1] how clearly an axis's scored views tell the scales apart: the grid's worst over best
  // miss, less 1 (0 before kMinScaleFrames).
  double Sharpness(const Axis& a) const;
  // Per axis, the scale its views are reconstructed with from the next frame on: its own best
  // once clearly better, or, while its views tell far less than the other's, the other's.
  void ChooseScales();

  ServoBeliefOptions options_;
  std::vector<double> scales_;  // [1] the grid of calibration scales, scales_[0] = 1
  std::vector<double> shares_;  // DelayShares of the delay range
  std::deque<Command> sent_;
  std::int64_t next_order_ = 0;
  std::int64_t exposed_ = 0;
  std::array<Axis, 2> axes_;  // pan, tilt
  ServoTargets believed_;
};

}  // namespace kapfix
