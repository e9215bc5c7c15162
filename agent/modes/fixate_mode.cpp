#include "agent/modes/fixate_mode.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "agent/modes/report_messages.hpp"
#include "agent/modes/run_options.hpp"
#include "common/fixation/patch_self_confidence.hpp"

namespace kapfix::agent {
namespace {

// [frames] the least spacing of the log's off-target lines (5 s at 30 fps).
constexpr std::uint64_t kOffTargetLogFrames = 150;
// [px/frame] a view moving at least this fast smears the reference's patch over a few px
// within an exposure of a fraction of the frame period. Jitter stays below it (σ = 2 px
// moves σ = 2.8 px a frame, under 8 px in 99.6 % of frames: SwingPredictorOptions).
constexpr double kSmearingSpeedPx = 8.0;

}  // namespace

void FixateMode::Enter(const CapturedFrame& frame, const ServoTargets& current) {
  reference_frame_ = frame.image.clone();
  reference_index_ = frame.index;
  reference_seen_at_ = {0, 0};
  reference_angles_ = current;
  Build();
  if (kind_ != AgentMode::kFixate) return;
  context_.events().OnReferenceTaken(reference_frame_, current);
  HoldByASurePatch(frame.index);
}

void FixateMode::SeeBefore(const CapturedFrame& frame) {
  // A reference taken while the view moves fast carries the motion's blur, and on a façade or
  // a repetitive scene the sharp frames of a held view may then never match it clearly:
  // realistic world, a reference taken a frame into the swing (kapfix-bench-loop --start
  // moving) lost leuvenA.jpg on 9 seeds of 10, where the first frame (no blur) held it.
  if (kind_ != AgentMode::kFixate) return;
  const std::optional<cv::Point2d> moved = loop_->Locate(frame.image);
  const double speed_px = moved ? std::hypot(moved->x, moved->y) : 0.0;
  if (speed_px < kSmearingSpeedPx) return;
  spdlog::warn(
      "frame {}: the view moved {:.0f} px in the frame before the reference, so the reference "
      "may be smeared by motion blur; if the lock does not come, fixate again while the view "
      "is slow (at the turn of the swing)",
      reference_index_, speed_px);
}

void FixateMode::HoldByASurePatch(std::uint64_t frame_index) {
  // SSP judged the slice over the free swing; the patch is whatever part of the scene is under
  // it now. One the search barely finds in its own frame will not confirm a lock in flight.
  const FixationOptions& options = loop_->options();
  const SearchStrategy& strategy = *context_.strategy();
  const int slice = options.slice;
  const double least = options.lock_regain_confidence;
  // One search when the patch passes, as it mostly does; every slice's only when it does not.
  if (PatchSelfConfidence(reference_frame_, slice, options, strategy) >= least) return;
  const std::vector<double> confidences = PatchSelfConfidences(reference_frame_, options, strategy);
  const double confidence = confidences.at(static_cast<std::size_t>(slice - 1));
  // SSP's recommendation gives way along SSP's ranking, as the benchmark's start after SSP
  // does; any other slice to the nearest that passes.
  const std::vector<int>& ranking = context_.slice_ranking();
  // (A ranking of another slice count is of settings no longer in force.)
  const bool ssps = ranking.size() == confidences.size() && ranking.front() == slice;
  const std::optional<int> sure = ssps ? FirstConfidentSlice(confidences, ranking, least)
                                       : NearestConfidentSlice(confidences, slice, least);
  const char* const which = ssps ? "the next in SSP's ranking" : "the nearest";
  const std::string weak = fmt::format(
      "frame {}: slice {}'s patch is weak here: the search finds it in its own frame at "
      "confidence {:.2f}, and a lock is confirmed at {:.2f}",
      frame_index, slice, confidence, least);
  if (!sure) {
    spdlog::warn("{}, so the lock may never come; no slice's patch is found surely here", weak);
    return;
  }
  const double found = confidences.at(static_cast<std::size_t>(*sure - 1));
  if (slice_choice_ == SliceChoice::kOperators) {
    spdlog::warn(
        "{}, so the lock may never come; slice {} is {} found surely ({:.2f}): select it "
        "(select_slice) if the lock does not come",
        weak, *sure, which, found);
    return;
  }
  spdlog::warn(
      "{}: the same view is held by slice {}'s patch instead, {} found surely ({:.2f}; "
      "select_slice {} overrides)",
      weak, *sure, which, found, slice);
  context_.SetSlice(*sure);
  Build();
}

void FixateMode::TakeUp(const HeldView& view) {
  reference_frame_ = view.reference_frame;
  reference_index_ = view.reference_index;
  reference_seen_at_ = view.seen_at;
  reference_angles_.reset();
  Build();
  if (view.seek_from) loop_->SeekFrom(*view.seek_from);
}

void FixateMode::Build() {
  loop_ = context_.MakeLoop(kind_ == AgentMode::kFollow ? FixationOptions::Reference::kPrevious
                                                        : FixationOptions::Reference::kStored);
  // The view to hold is the one the operator fixated, not the one in front of the camera
  // when a setting changed.
  if (!reference_frame_.empty()) loop_->SetReference(reference_frame_, reference_angles_);
  lost_lock_ssp_.reset();
  const LostLockSspOptions options = MakeLostLockSspOptions(context_.settings());
  if (kind_ != AgentMode::kFixate || options.after_frames == 0) return;
  ssp_strategy_ = context_.strategy();
  lost_lock_ssp_.emplace(*ssp_strategy_, options);
}

void FixateMode::SeeLostLock(const CapturedFrame& frame, bool lock_lost) {
  if (!lost_lock_ssp_) return;
  const bool was_running = lost_lock_ssp_->running();
  const std::optional<SliceSelection> selection =
      lost_lock_ssp_->See(lock_lost, [&] { return context_.Plane(frame.image); });
  if (!was_running && lost_lock_ssp_->running()) {
    spdlog::info(
        "frame {}: the lock has stayed lost for {:.1f} s on slice {}: SSP runs over the swing "
        "the servos now leave free",
        frame.index, (lost_lock_ssp_->lost_frames() - 1) * context_.options().frame_period_s,
        context_.slice());
  }
  if (!selection) return;
  SwingProgress progress;
  progress.done = selection->frames_used;
  progress.total = selection->frames_used;
  progress.finished = true;
  context_.events().OnSliceReport(
      MakeSliceReport(*selection, MakeSliceReportContext(context_.settings().search), progress));
  // Next in SSP's ranking after the slice just lost comes the first whose patch the search
  // finds surely in the reference frame, the view held.
  const int from = context_.slice();
  const std::optional<int> next = ConfidentSliceBesides(reference_frame_, selection->ranking, from,
                                                        loop_->options(), *ssp_strategy_);
  if (!next) return;  // one slice: nothing else to try
  const int to = *next;
  spdlog::warn(
      "frame {}: SSP over the {} frames of the lost lock recommends slice {}{}: the same view is "
      "now held by slice {}'s patch instead of slice {}'s (select_slice overrides)",
      frame.index, selection->frames_used, selection->best_slice,
      selection->best_slice == to ? std::string()
                                  : fmt::format(", and slice {} is the first after it the "
                                                "search finds surely in the view held",
                                                to),
      to, from);
  // The swing's centre is in servo angles, the same whichever patch holds the view.
  const std::optional<ServoTargets> centre = loop_->swing_centre();
  context_.SetSlice(to);
  context_.events().OnModeChanged(kind_, to);
  Build();
  if (centre) loop_->KeepSwingCentre(*centre);
  lock_lost_ = false;  // the new patch's lock starts unconfirmed, not lost
}

void FixateMode::OnSettings(bool rebuild) {
  if (rebuild) {
    Build();
  } else {
    loop_->SetGains(MakeGains(context_.settings().gains));  // bumpless
  }
}

std::optional<HeldView> FixateMode::HeldFixation() const {
  if (kind_ != AgentMode::kFixate || reference_frame_.empty()) return std::nullopt;
  return HeldView{.reference_frame = reference_frame_,
                  .reference_index = reference_index_,
                  .slice = context_.slice(),
                  .seek_from = std::nullopt,
                  .seen_at = reference_seen_at_};
}

FrameOutcome FixateMode::Process(const CapturedFrame& frame, const ServoTargets& current,
                                 double dt_s) {
  FrameOutcome outcome;
  outcome.step = loop_->Process(frame.image, current, dt_s);
  // The operator must hear of a lock the agent does not trust (issue 9), once per change;
  // telemetry carries it on every frame as lock_lost.
  if (outcome.step.lock_lost != lock_lost_) {
    lock_lost_ = outcome.step.lock_lost;
    if (lock_lost_) {
      spdlog::warn(
          "frame {}: match not trusted (confidence {:.2f}, ambiguous or poor): re-acquiring the "
          "stored reference; {}",
          frame.index, outcome.step.match.confidence,
          loop_->swing_centre() ? "the servos head for the centre of the view's swing seen so far"
                                : "the servos hold (no swing of this view seen yet)");
    } else {
      spdlog::info("frame {}: stored reference re-acquired, lock trusted again", frame.index);
    }
  }
  // Held lock, right match, view farther than the off-target distance: the loop trails the
  // view (a gust, the pull-in) and says so. Telemetry carries off_target on every frame; the
  // log says when it starts, at most once per kOffTargetLogFrames with the count since the last
  // line, or a gusty flight would write a line every few frames.
  const FixationLoop::Step& step = outcome.step;
  // A lock riding out untrusted frames steers by the trusted ones but claims none of them.
  const bool trailing = !step.lock_lost && step.trusted && step.off_target;
  off_target_frames_ += step.off_target ? 1 : 0;
  const bool quiet_long_enough =
      !last_off_target_log_ || frame.index >= *last_off_target_log_ + kOffTargetLogFrames;
  if (trailing && !trailing_ && quiet_long_enough) {
    const double off_px = std::hypot(step.match.displacement.x, step.match.displacement.y);
    if (step.partial) {
      spdlog::info(
          "frame {}: steering along {} only, not claimed: the patch is placed surely across its "
          "stripes but hardly along them (confidence x {:.2f}, y {:.2f}); the other axis coasts "
          "on the forecast or holds; {} frames off target since the last such line",
          frame.index, step.trusted_x ? "x" : "y", step.match.confidence_x, step.match.confidence_y,
          off_target_frames_);
    } else if (step.riding_out) {
      spdlog::info(
          "frame {}: view {:.1f} px off, not claimed: the lock rides out untrusted frames until "
          "{} clear ones in a row; {} frames off target since the last such line",
          frame.index, off_px, loop_->options().lock_regain_frames, off_target_frames_);
    } else {
      spdlog::info(
          "frame {}: view {:.1f} px off target, the loop trails it (lock held); {} frames off "
          "target since the last such line",
          frame.index, off_px, off_target_frames_);
    }
    last_off_target_log_ = frame.index;
    off_target_frames_ = 0;
  }
  trailing_ = trailing;
  outcome.mode = kind_;
  outcome.slice = context_.slice();
  outcome.slice_count = context_.settings().search.slices;
  outcome.patch = loop_->patch();
  if (kind_ == AgentMode::kFixate) {
    outcome.reference_frame = reference_index_;
    outcome.reference_seen_at = reference_seen_at_;
  }
  // Last: a slice changed here holds the view from the next frame on.
  SeeLostLock(frame, outcome.step.lock_lost);
  return outcome;
}

}  // namespace kapfix::agent
