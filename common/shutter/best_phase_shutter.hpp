#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "common/shutter/view_forecaster.hpp"

namespace kapfix {

enum class ShutterMode {
  kInterval,   // at once, on the frame after the request
  kBestPhase,  // at the quietest predicted moment of a window
};

// "interval" or "best-phase" (the settings schema's words); nothing for another.
std::optional<ShutterMode> ParseShutterMode(std::string_view text);

struct BestPhaseShutterOptions {
  ShutterMode mode = ShutterMode::kInterval;
  double window_s = 0;               // [s] how long a request may wait; 0 = one swing period
  double window_cap_s = 10;          // [s] longest wait; a longer window_s is refused
  double exposure_ms = 10;           // [ms] exposure the photo is planned for (and blurred over)
  double frame_period_s = 1.0 / 30;  // [s] the camera's frame period
  // [px] residual offset within which the photo is on target: its framing has not visibly
  // moved (the station's off-target threshold, a tenth of the thesis' 100 px patch). An
  // offset inside it is invisible in the photo, so it costs nothing: trading visible smear
  // for it would make the photo worse.
  double on_target_px = 10;
  // [px of blur per px of offset] weight of the offset beyond on_target_px against the view's
  // travel during the exposure: one pixel of travel (the station's blurred threshold, where
  // the smear of a point covers two pixels) weighs as much as a whole tolerance (10 px) more
  // off target.
  double offset_weight = 0.1;
  int scenarios = 64;  // [1] draws of the forecast's error the choice averages over
  std::uint32_t seed = 1;

  // Window 0 or 0.1 s…cap, cap 0.5…30 s, exposure 0.01…2000 ms (the settings schema's
  // ranges, checked by the caller), frame period > 0, tolerance and weight ≥ 0, 1…4096
  // scenarios; and the window not longer than the cap.
  bool IsValid(std::string* error) const;

  // [s] the exposure; the simulated camera blurs its frames over it too.
  double exposure_s() const { return exposure_ms / 1000.0; }

  // The operator-set fields by the names of their settings (kapfix.v1.PhotoSettings), listed
  // once so that the agent copies its settings in by name.
  template <typename Visitor>
  void VisitFields(Visitor&& visit) {
    visit("shutter", mode, ParseShutterMode);
    visit("window_s", window_s);
    visit("window_cap_s", window_cap_s);
    visit("exposure_ms", exposure_ms);
  }
};

// A photo the shutter fired, with the loop's state on its frame.
struct ShutterShot {
  double wait_s = 0;              // [s] from the window's opening (the request) to this frame
  std::string reason;             // why now
  double offset_px = 0;           // [px] |residual offset| measured on the frame
  double speed_px_per_frame = 0;  // [px/frame] residual view speed: the offset's change since
                                  // the frame before (0 when that was not measured)
  double blur_px = 0;             // [px] view travel during the exposure at that speed
  bool lock_lost = false;         // the frame's match was not trusted
  // What the shot was planned with (the photo's metadata carries them).
  ShutterMode mode = ShutterMode::kInterval;
  double exposure_ms = 0;  // [ms]
};

// The swing-phase shutter (issue 13). A request opens a window (window_s, or one swing
// period as the forecaster sees it, at most window_cap_s); on each frame in it the shutter
// either fires or waits. The cost of a frame is its view travel during the exposure plus
// offset_weight × its residual offset beyond on_target_px (an on-target offset costs
// nothing: the photo's framing has not visibly moved, its smear shows). The frame in hand is
// measured: the view's speed over it is the change of the measured offset since the frame
// before, which is exactly the motion its exposure saw. The frames to come are forecast: the
// forecaster's path plus its measured one-step error, drawn `scenarios` times with a fixed
// seed. The shutter fires when the frame in hand costs no more than waiting is expected to
// (backward induction over the window's remaining frames: the last one is taken whatever it
// costs, each earlier one only if it beats the expected cost of going on). So it decides on
// the frame itself, never on the one after, and a forecast of a quieter phase ahead makes it
// wait.
//  - No trained forecaster (or no swing period for a window of one period): fires at once.
//  - Untrusted frames are never chosen; a window with no trusted frame fires at its end.
//  - Interval mode: fires on the first frame after the request.
// Not thread-safe: the control thread owns it.
class BestPhaseShutter {
 public:
  // `forecaster` is fed every frame by OnFrame and must outlive the shutter. Throws
  // std::invalid_argument for options that are not IsValid.
  BestPhaseShutter(ViewForecaster& forecaster, BestPhaseShutterOptions options = {});

  // Takes effect for the next window; an open window keeps its end. Throws as the
  // constructor.
  void SetOptions(const BestPhaseShutterOptions& options);
  const BestPhaseShutterOptions& options() const { return options_; }

  // A photo is wanted: opens a window at the next frame unless one is open (requests while
  // it is open share its photo).
  void Request();
  bool window_open() const { return open_ || requested_; }

  // Every frame, in order. The shot when the shutter fires on this frame.
  std::optional<ShutterShot> OnFrame(const ShutterFrame& frame);

  // [px] expected cost of the frames after the newest one if the shutter waits for the best
  // of them, `frames` (≥ 1) of them left; what OnFrame compares the frame in hand with.
  double ExpectedCostOfWaiting(const ShutterFrame& frame, int frames) const;
  // [px] a frame's cost from its speed and offset.
  double Cost(double speed_px_per_frame, double offset_px) const;

 private:
  // This frame's choice; previous_ is still the frame before.
  std::optional<ShutterShot> Decide(const ShutterFrame& frame);
  ShutterShot Fire(const ShutterFrame& frame, std::string reason);

  ViewForecaster& forecaster_;
  BestPhaseShutterOptions options_;
  bool requested_ = false;
  bool open_ = false;
  std::int64_t opened_us_ = 0;
  std::int64_t deadline_us_ = 0;
  bool trusted_in_window_ = false;
  std::optional<ShutterFrame> previous_;  // the frame before, for the speed
};

}  // namespace kapfix
