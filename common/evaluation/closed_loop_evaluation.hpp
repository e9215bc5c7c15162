#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "common/control/controller.hpp"
#include "common/control/predictive_controller.hpp"
#include "common/fixation/fixation_loop.hpp"
#include "common/sim/simulated_platform.hpp"
#include "common/sim/world_options.hpp"

namespace kapfix {

// A closed-loop flight in simulation (SPEC §3, issue 3 "Closed-loop figures"), headless.
// The defaults are the kite scene: SPEC §3's swing (A = 100 px, T = 40 frames,
// τ = 400 frames, Y jitter σ = 2 px, noise σ = 3, brightness ±8 %) with gusts on, servos with
// one frame of latency (SimulatedServoOptions' defaults), 10 px per degree, the predictive
// controller with an exact calibration, strategy pyr, 100×100 patch on slice 5.
//
// The kite searches both axes, not X alone as SPEC §2.3 has it for a kite: the reference
// frame carries its own Y jitter (σ = 2 px; 4.1 px at seed 1), and only a measured Y lets the
// tilt servo hold the view there — X-only leaves that offset plus the jitter in the figure
// (kite seed 1: 4.65 px RMS in Y alone instead of 2.15). It costs pyr a joint coarse scan.
struct ClosedLoopOptions {
  SimulatedPlatformOptions platform = [] {
    SimulatedPlatformOptions o;
    o.kite.gusts = true;
    return o;
  }();
  FixationOptions fixation = [] {
    FixationOptions o;
    o.search.axis = SearchAxis::kBoth;
    return o;
  }();
  std::string strategy = "pyr";
  std::string controller = "predictive";  // or "p", "pid"
  ControllerGains gains;
  // lead_frames is set from the pan servo's latency (1 + latency) when left at 0, and
  // lead_jitter_frames then from its jitter (latency_max_frames − latency_frames).
  PredictiveOptions predictive = [] {
    PredictiveOptions o;
    o.predictor.lead_frames = 0;
    return o;
  }();
  // The controller's deg per px is calibration_scale · world.calibration_error / px_per_deg:
  // 1 is an exact calibration, 1.1 one that over-corrects by 10 %.
  double calibration_scale = 1.0;
  // The field's disturbances (issue 9), applied to `platform` by EvaluateClosedLoop; the
  // default is the nominal world (the platform options as they are).
  WorldOptions world;
  // How fixation starts (issue 9: both count): from the first frame, as `--mode fixate`, or
  // after SSP: the servos hold through ssp_frames of free swing (FreeSwingSlice), the loop
  // fixates the slice SSP recommends, and the frame after the swing becomes the reference.
  // Moving: from the frame after the first, as an operator who fixates while the rig already
  // swings. The simulated platform starts at frame 0, so nothing moved before it and the
  // first frame carries no motion blur; the second carries the swing's (--blur), as a
  // reference taken mid-swing does.
  enum class Start { kFirstFrame, kAfterSsp, kMoving };
  Start start = Start::kFirstFrame;
  int ssp_frames = 300;  // [frames] the free swing (the agent's default SSP deadline)
  // From the first frame or moving: the fixated slice is the operator's (select_slice) and is
  // kept though its patch is weak in the reference; otherwise it is the agent's, and a weak
  // patch gives way to the nearest slice whose patch the search finds surely
  // (NearestConfidentSlice), as the agent's fixate does.
  bool keep_slice = false;
  // [frames] a lock lost this long runs SSP over the ssp_frames that follow and moves the
  // fixation to its slice on the same reference (LostLockSsp, as the agent's fixate); 0 = never.
  int ssp_after_lost_frames = 0;
  int frames = 600;              // frames processed after the reference frame
  double frame_period_s = 0.04;  // [s] dt handed to the controller (25 frames/s)

  // Also checks that the strategy and controller names are known.
  bool IsValid(std::string* error) const;

  // The defaults for a motion: the kite's as above; a boat rolls along Y, so the search
  // (and the control) is along Y, and the swing model gets the order its three superposed
  // waves need (AR(8) over 160 frames: 1.0 px RMS in Y where AR(2) leaves 3.5 px).
  static ClosedLoopOptions ForMotion(SimulatedPlatformOptions::Motion motion);
};

struct ClosedLoopFigures {
  double rms_error_px = 0;      // [px] RMS over frames of |ViewOffset| after the reference
  double rms_error_x_px = 0;    // [px] its x component alone
  double rms_error_y_px = 0;    // [px] its y component alone
  double open_loop_rms_px = 0;  // [px] the same for the motion alone (servos off), for scale
  // [px] what even a loop that knew the swing's future would leave to the servo's latency
  // jitter (AimFloorRms over the open-loop offsets; 0 at a fixed latency): the world's floor.
  double aim_floor_rms_px = 0;
  double lock_lost_pct = 0;  // [%] frames reported lock lost
  double p95_error_px = 0;   // [px] 95th percentile of |ViewOffset| over the frames
  // [%] frames whose true view error |ViewOffset| > 10 px (gross), and of those the ones the
  // loop claimed to hold the view (Step::off_target false: lock held, match trusted, measured
  // within FixationOptions::off_target_px), both as a share of all frames. A frame the camera
  // dropped counts in gross but is never silent: the loop saw nothing and claimed nothing for
  // it (the agent's flight report has no record of it; its telemetry's sequence shows the gap).
  double gross_pct = 0;
  double silent_gross_pct = 0;
  // [%] the gross frames with lock_lost false alone (the first reading, which also
  // counts the frames where the loop knew and said it was off target), of all frames.
  double gross_lock_held_pct = 0;
  double off_target_pct = 0;  // [%] frames the loop said it was off target (lost included)
  double dropped_pct = 0;     // [%] frames the camera lost (world.frame_drops)
  // [px] RMS of the measured displacement's miss (measured − true) over the frames with a
  // match: what image disturbances (roll, blur, exposure) cost the matcher.
  double measurement_rms_px = 0;
  // [px] the same miss against the fixated slice's own true motion. The view error above is
  // the frame centre's; roll turns the image about that centre, so a patch r px off it moves
  // by about roll × r more (3° at 100 px: 5 px), which no pan/tilt match can tell from a
  // shift. This is the matcher's own miss (keystone left out: < 0.1 px).
  double slice_miss_rms_px = 0;
  // [1] 1 − the mean match confidence over the frames with a match: how much less sure of
  // itself the matcher is (motion blur smears without moving the minimum).
  double confidence_loss = 0;
  int frames = 0;
  int slice = 0;                   // the slice fixated (options.fixation's, or SSP's choice)
  int slices_after_lost_lock = 0;  // moves to another slice by SSP after a lost lock
  double fps = 0;                  // frames per wall-clock second of Process()
  double loop_latency_p50_ms = 0, loop_latency_p99_ms = 0;  // [ms] of Process()
  // [1] the predictive controller's final online estimate of the pan axis's deg per px ÷ the
  // true value (1 = perfect); NaN for the other controllers.
  double deg_per_px_estimate_ratio = 0;
  double deg_per_px_estimate_sigma = 0;  // [1] its relative standard deviation
  bool deg_per_px_estimate_trusted = false;
  double predicting_pct = 0;  // [%] frames where the predictive controller used its forecast
  std::vector<cv::Point2d> view_offsets;  // [px] ViewOffset of each processed frame
  std::vector<cv::Point2d> open_offsets;  // [px] OpenLoopOffset of each (the motion alone)
  std::vector<double> measured_x;         // [px] measured displacement x (NaN: not found)
  std::vector<double> measured_y;         // [px] measured displacement y (NaN: not found)
  std::vector<double> confidence;         // [0, 1] the match's confidence (NaN: dropped)
  std::vector<bool> lock_lost;            // Step::lock_lost of each frame (dropped: standing)
  std::vector<bool> off_target;           // Step::off_target of each frame (dropped: standing)
  std::vector<ServoTargets> angles;       // [deg] servo output angles each frame was seen by
  std::vector<ServoTargets> believed;     // [deg] what the loop believed them to be
  std::vector<ServoTargets> commanded;    // [deg] what it commanded after the frame (as sent)
  // [deg] the roll since the reference the loop read for its claim (Step::roll_deg; NaN: not
  // read, or dropped) and the truth in the same convention (the content's turn, +x towards
  // +y: the camera's roll since the reference, negated)
  std::vector<double> roll_read_deg;
  std::vector<double> roll_true_deg;
  // The predictive controller's axes after each frame (NaN: another controller, or a
  // dropped frame): what each acted on (0 plain P, 1 the last step extrapolated, 2 the swing
  // model; SwingPredictor::Forecaster), the forecast's weight against P [0, 1], and the
  // calibration it acts on ÷ the true deg/px, and the servo belief's (ServoBelief::scale) ÷ the
  // true deg/px.
  struct AxisForecast {
    double forecaster, weight, calibration_ratio, belief_calibration_ratio;
  };
  std::vector<AxisForecast> pan_forecast;
  std::vector<AxisForecast> tilt_forecast;
};

// Runs the loop: frame 0 (after SSP: the frame after the free swing) becomes the reference,
// and view errors are taken against its view; then per frame Step (servos act),
// CaptureFrame, FixationLoop::Process, and the targets are commanded. The controller is
// never told the servos' true angles, which a hobby servo cannot report: it gets the command
// that should have taken effect by the frame's capture (the one sent 1 + the servo's nominal
// latency frames earlier), as the agent's pipeline does. A frame the camera drops is not
// processed (no command; the next frame's dt is two frame periods) but its view error counts.
// Throws std::invalid_argument for an empty scene or options that are not IsValid.
ClosedLoopFigures EvaluateClosedLoop(const cv::Mat& scene_bgr, const ClosedLoopOptions& options,
                                     const std::function<void(int, int)>& progress = nullptr);

}  // namespace kapfix
