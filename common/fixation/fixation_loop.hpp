#pragma once

#include <deque>
#include <limits>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "common/control/controller.hpp"
#include "common/control/lens_calibration.hpp"
#include "common/fixation/patch_roll.hpp"
#include "common/fixation/rolling_reference.hpp"
#include "common/image/color_channel.hpp"
#include "common/matching/exposure_compensation.hpp"
#include "common/matching/reference_patch.hpp"
#include "common/sampling/sampling_pattern.hpp"
#include "common/search/search_strategy.hpp"

namespace kapfix {

struct FixationOptions {
  // Axis, range and sub-pixel of the search. Only the searched axes are controlled: an axis
  // that is not searched (Y of a kite's kX) reaches the controller as 0 and its servo holds.
  SearchOptions search;
  SamplingOptions sampling;
  ColorChannel channel = ColorChannel::kGreen;
  int patch_size = 100;  // [px] side of the square reference patch
  int slice_count = 9;   // N slices (SPEC §1)
  int slice = 5;         // 1 = top … slice_count; SSP chooses it
  // A frame whose match confidence is below this (or that found no match) is not trusted:
  // the controller gets it as not found. After lock_lost_frames such frames in a row the
  // lock is reported lost (the agent then re-runs SSP, SPEC §2.6), whether or not it was
  // confirmed (see lock_regain_confidence). Only lock_regain_frames clear frames in a row end
  // such a run: single good frames between bad ones do not.
  // MatchConfidence sees a repetitive texture's rival (issue 9): below this the match is
  // ambiguous or poor and must not steer the servos. A confirmed lock on a stored reference
  // judges each searched axis alone (SearchResult::confidence_x/y): a frame sure along one
  // axis only steers that axis, keeps the lock, and is never claimed (Step::partial).
  double lock_lost_confidence = 0.2;
  // Off: a frame is trusted only when it is sure along every searched axis (before session 23).
  bool axis_trust = true;
  int lock_lost_frames = 5;
  // Once the lock is lost the loop re-acquires the stored reference: each search is centred
  // on search.origin (where the reference was) with its range widened by this factor, as far
  // as the frame allows, and the lock is back only after lock_regain_frames trusted frames
  // in a row (a single lucky frame on a repetitive texture must not snap to a neighbour).
  double reacquire_range_factor = 2.0;
  int lock_regain_frames = 3;
  // [frames] While the lock is lost the servos head for the centre of the swing seen while the
  // view was tracked (stored reference only): the mean, over the last this many trusted
  // frames and the reference frame itself, of the angles that would have centred the view
  // (the angles seen through plus the measured displacement in degrees). Held still there,
  // the view swings about the reference instead of about the point where the reference was
  // taken, which may be the swing's far end (left01.jpg after SSP, seed 1: 48.6 px RMS with
  // the servos back at the reference's angles, against 26.1 px about the swing's centre).
  // A few periods of a kite's swing; 1 returns to the last trusted frame's view.
  int swing_centre_frames = 300;
  // A lock is confirmed (after the reference, or when re-acquired) only by lock_regain_frames
  // frames in a row at or above this confidence, a margin above lock_lost_confidence
  // (hysteresis): on a repetitive texture the confidence hovers around the trust threshold
  // (building.jpg: 0.05-0.3, clean photos 0.4-0.8) and a lock made of frames that barely pass
  // it is not one: until confirmed it steers by both axes or none (axis_trust). A lock that
  // rides out untrusted frames claims none of its frames (Step::riding_out), so a view that
  // never really locked is never held silently; until session 23 an unconfirmed lock was lost
  // at its first untrusted frame instead, and a lock-on's motion blur alone made one
  // (stuff.jpg, realistic world, seed 3: right matches at 36 px a frame, confidence 0.04,
  // the lock back only 12 frames later with the view 113 px off).
  double lock_regain_confidence = 0.4;
  // [px] A re-acquired reference steers the servos back at once, but the lock counts as held
  // again (lock_lost false) only once the measured displacement is within this: found 60 px
  // away, the view is not held yet (stored reference only; follow has no such view).
  double lock_regain_px = 10;
  // [px] The loop says it holds the view (Step::off_target false) only while the lock is held
  // (not riding out untrusted frames), this frame's match is trusted and its measured displacement
  // is within this. A right match that measures the view 25 px away (the loop trailing a gust, the
  // first frames of the pull-in) is no lost lock, but it is no held view either, and the operator
  // must hear so. Below the report's 10 px gross threshold by the matcher's miss (0.1-0.5 px RMS in
  // the simulated worlds) and a margin, so that a frame claimed on target is not 10.3 px off.
  double off_target_px = 8;
  // The claim allows for roll (stored reference only): a patch held r px from the frame
  // centre leaves the centre roll × r off, so when a roll within roll.max_deg could carry the
  // centre beyond off_target_px, the roll is read from the patch (ReadPatchRoll) and the
  // centre's displacement (CentreDisplacement) must be within it too: a patch held beside a
  // centre that is not is no held view. A patch measured beyond the line is never claimed,
  // whatever roll is read: on a façade's repeats the roll read can be confidently wrong
  // (building.jpg, no roll at all: 2-3.5°), and it made claims at 10-14 px. Off: the patch's
  // displacement alone.
  bool roll_aware_claim = true;
  PatchRollOptions roll;
  // The stored reference turned by the roll read while flying (RollingReference): the search
  // compares each frame with the reference as the rolled camera sees it.
  RollTrackingOptions roll_tracking;
  // Scale each frame to the stored reference's mean brightness before the search
  // (ExposureCompensation): an auto-exposure step between the reference and the frame
  // otherwise pulls the SSD minimum off the view while the match stays confident.
  bool compensate_exposure = true;
  enum class Reference {
    kStored,    // fixate: every frame is compared with the reference stored by SetReference
    kPrevious,  // follow: each frame is compared with the previous one (a moving boat)
  };
  Reference reference = Reference::kStored;
  // Centre each search on the previous trusted match's shift instead of search.origin: the
  // view moves little between frames, so the window stays centred on the answer even while
  // the loop still trails the swing. (Follow compares consecutive frames, whose step is
  // small: it always searches around search.origin.)
  bool track_origin = true;
  // [frames] follow only: the frame-to-frame displacements are summed with this leak time
  // constant into a displacement from a reference that slowly moves with the boat's course,
  // which is what the controllers act on.
  double follow_decay_frames = 50;

  bool IsValid(std::string* error) const;
};

// One frame of fixation (SPEC §2.8, §4 "fixate"/"follow"), pure: measure the displacement of
// the reference patch in the frame, then ask the controller for servo targets. A match that
// is not trusted never steers: the controller gets it as missing (the predictive one follows
// its forecast for a few frames, then the servos hold), and after lock_lost_frames of them
// the lock is reported lost and the search re-acquires the stored reference, while the
// servos head back to the angles the reference was seen through (when known), so that the
// view swings past it. No threads,
// no I/O; not thread-safe (one control thread owns it). The caller sends the targets to the
// servos, whose driver enforces the hard limits.
class FixationLoop {
 public:
  // Throws std::invalid_argument for options or a calibration that are not IsValid, or a
  // null strategy or controller. The calibration is handed to the controller.
  FixationLoop(FixationOptions options, std::shared_ptr<const SearchStrategy> strategy,
               std::unique_ptr<Controller> controller, LensCalibration calibration);

  // Stores the reference patch at the slice of `frame_bgr` (BGR or grey, 8 bit) and resets
  // the controller and the lock. `seen_through` [deg]: the servo angles the frame was
  // captured through, the first sample of the swing's centre a lost lock heads for
  // (swing_centre); unknown (a view taken up after a restart): a lost lock holds the servos
  // until a frame is trusted.
  // Throws std::invalid_argument when the patch does not fit.
  void SetReference(const cv::Mat& frame_bgr,
                    std::optional<ServoTargets> seen_through = std::nullopt);
  // [px] Where the reference's patch lies in `frame_bgr` (stored-reference convention, on the
  // searched axes), when the search finds it clearly (lock_regain_confidence); none without a
  // reference or a clear match. The lock and the controller are left alone: for a frame
  // outside the flight, such as the one before the reference (how fast the view was moving
  // when it was taken).
  std::optional<cv::Point2d> Locate(const cv::Mat& frame_bgr) const;
  bool has_reference() const { return reference_.has_reference(); }
  // Centres the next search on `shift` [px] instead of search.origin: the reference's view was
  // found there by a wider search (an agent resuming after a restart, issue 14). With
  // track_origin the searches then follow the view from there.
  void SeekFrom(cv::Point shift) { origin_ = shift; }
  cv::Rect patch() const { return patch_; }  // [px] the patch in the reference frame

  struct Step {
    SearchResult match;    // displacement in the stored-reference convention (follow: step)
    ServoTargets targets;  // [deg] what to command now
    bool lock_lost = false;
    // The match steered the servos this frame on at least one axis (confident, and the lock
    // not being re-acquired).
    bool trusted = false;
    // Per searched axis, the match steered that axis's servo. With a stored reference a
    // confirmed lock is steered along the axis its match is sure of while the other coasts on
    // the controller's forecast or holds (SearchResult::confidence_x/y: a patch of stripes is
    // placed surely across them only); such a frame keeps the lock but is never claimed.
    // An axis not searched is never trusted.
    bool trusted_x = false;
    bool trusted_y = false;
    bool partial = false;      // trusted along one of two searched axes only
    bool reacquiring = false;  // the search was widened around the stored reference
    // The loop does not claim to hold the view: the lock is lost or riding out untrusted
    // frames, this frame's match is not trusted, or it measures the view farther than
    // off_target_px (issue 9's honest lock).
    bool off_target = true;
    // The lock rides out untrusted frames (after one, until lock_regain_frames clear frames in
    // a row): the trusted frames between still steer, but none is claimed (off_target).
    bool riding_out = false;
    // [deg] the roll read from the patch for the claim above; NaN when it was not needed
    // (the patch's displacement alone decided) or could not be read.
    double roll_deg = std::numeric_limits<double>::quiet_NaN();
    // [deg] the roll tracked since the reference (RollingReference::estimate_deg) after this
    // frame's read; NaN when it was not read (no confident match, or tracking off).
    double tracked_roll_deg = std::numeric_limits<double>::quiet_NaN();
    double exposure_gain = 1;  // [1] the factor the frame was scaled by before the search
    double loop_us = 0;        // [µs] wall time of this Process call
    // What the controller believes after this frame (online deg/px, forecast weight), for
    // telemetry and the flight report; none for a controller that does not learn in flight.
    std::optional<ControlEstimate> estimate;
  };
  // `current`: the servo angles `frame_bgr` was captured through; `dt_s`: time since the
  // previous frame. Without a reference the servos hold and the lock is reported lost.
  Step Process(const cv::Mat& frame_bgr, const ServoTargets& current, double dt_s);
  // [deg] Where a lost lock sends the servos (stored reference): the centre of the swing seen
  // while the view was tracked (swing_centre_frames); none when neither the reference's
  // angles nor a trusted frame are known (a lost lock then holds the servos).
  std::optional<ServoTargets> swing_centre() const;
  // The same view held before by another patch (SSP after a lost lock): until this loop's lock
  // is confirmed, its swing centre is `centre` [deg], and its unconfirmed frames, which may sit a
  // texture period off, add nothing to it (left05.jpg, boat: they drove the servos 11° off).
  void KeepSwingCentre(const ServoTargets& centre);

  void SetCalibration(const LensCalibration& calibration);
  // New operator gains for the controller, keeping its history (bumpless; issue 15 item 7).
  void SetGains(const ControllerGains& gains) { controller_->SetGains(gains); }
  const FixationOptions& options() const { return options_; }
  const Controller& controller() const { return *controller_; }

 private:
  cv::Mat Plane(const cv::Mat& frame_bgr) const;
  // The search for this frame: around the tracked origin, or widened around the stored
  // reference while re-acquiring (then marks `step` reacquiring).
  SearchOptions SearchWindow(cv::Size frame, bool stored, Step* step) const;
  // Counts clear and untrusted frames from `step`'s match, loses or regains the lock, and
  // sets `step`'s lock_lost and trusted.
  void UpdateLock(bool stored, Step* step);
  // Brightness of the reference plane `plane` for the next frames' compensation.
  void StoreExposure(const cv::Mat& plane);
  // Whether the view is held at the patch's measured `displacement` [px] (stored reference):
  // within off_target_px, the roll allowed for (roll_aware_claim); sets step->roll_deg.
  // `displacement` is the match's on both axes: a single-axis search's reading across it
  // (pyr's cross range) is no measurement to steer by, but it can show a view not held.
  bool HoldsView(const cv::Mat& plane, const cv::Point2d& displacement, Step* step) const;
  // [px] `displacement` with the axis that is not searched set to 0.
  cv::Point2d OnSearchedAxes(cv::Point2d displacement) const;
  // Adds this trusted frame's centring angles (`current` plus `displacement` in degrees,
  // through the controller's trusted estimate or the calibration) to the swing's centre.
  void AddCentreSample(const ServoTargets& current, const cv::Point2d& displacement);
  // Follow (previous-frame reference): adds `frame_step` [px] to the leaky sum, makes
  // `plane` the next reference, and returns the sum [px].
  cv::Point2d FollowStep(const cv::Mat& plane, const cv::Point2d& frame_step);

  FixationOptions options_;
  std::shared_ptr<const SearchStrategy> strategy_;
  std::unique_ptr<Controller> controller_;
  SampleSet samples_;
  cv::Rect patch_;
  RollingReference reference_;
  LensCalibration calibration_;
  // [deg] the angles that would have centred the view, per trusted frame (and the reference
  // frame's angles first), and their sum: the lost lock's return point is their mean.
  std::deque<ServoTargets> centre_samples_;
  ServoTargets centre_sum_;
  ExposureCompensation exposure_;  // to the reference's brightness (off: gain 1)
  cv::Point origin_{0, 0};
  cv::Point2d follow_sum_{0, 0};  // [px] leaky sum of the follow steps
  int untrusted_frames_ = 0;
  int clear_frames_ = 0;      // frames in a row at or above lock_regain_confidence
  bool confirmed_ = false;    // the lock has been confirmed since the reference or regain
  bool reacquiring_ = false;  // the lock was lost and is not yet regained
  std::optional<ServoTargets> kept_centre_;  // [deg] KeepSwingCentre's, until a confirmed lock
  bool returning_ = false;                   // re-acquired, the servos bringing the view back
};

}  // namespace kapfix
