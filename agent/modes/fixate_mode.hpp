#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>

#include "agent/modes/mode.hpp"
#include "agent/modes/mode_context.hpp"
#include "common/fixation/fixation_loop.hpp"
#include "common/selection/lost_lock_ssp.hpp"

namespace kapfix::agent {

// Fixate (SPEC §4): every frame is matched against the reference taken when fixate began, and
// the fixation loop turns the displacement into servo targets. Owns the loop, the reference
// and the lock state; new settings rebuild the loop on the same reference (new gains only:
// the controller keeps its state). A lock lost for search.ssp_after_lost_s runs SSP over the
// free swing that follows and moves the fixation to its slice, on the same reference frame.
class FixateMode : public Mode {
 public:
  // Whose the slice in use is as fixate begins. The operator's (select_slice of a slice other
  // than SSP's recommendation) is kept, with a warning when its patch is weak in the reference
  // frame. The agent's (the middle slice, SSP's recommendation, also when the operator confirms
  // it, the slice of an earlier fixation) gives way to another slice whose patch the search
  // finds surely there: the view held is the reference frame's either way, and a patch on a
  // plain wall or a smooth face would lose it from the first frame.
  enum class SliceChoice { kAgents, kOperators };

  explicit FixateMode(ModeContext& context, SliceChoice choice = SliceChoice::kAgents)
      : FixateMode(context, AgentMode::kFixate) {
    slice_choice_ = choice;
  }

  AgentMode kind() const override { return kind_; }
  // The reference is `frame` (ModeEvents::OnReferenceTaken tells).
  void Enter(const CapturedFrame& frame, const ServoTargets& current) override;
  // Warns when the view moved fast into the reference: its patch is then smeared.
  void SeeBefore(const CapturedFrame& frame) override;
  // Instead of Enter: the reference is a view held earlier, not the frame in front of the
  // camera (no OnReferenceTaken: the view is not new). Throws like Enter.
  void TakeUp(const HeldView& view);
  FrameOutcome Process(const CapturedFrame& frame, const ServoTargets& current,
                       double dt_s) override;
  void OnSettings(bool rebuild) override;
  std::optional<HeldView> HeldFixation() const override;

 protected:
  // Follow: the same loop against the previous frame.
  FixateMode(ModeContext& context, AgentMode kind) : context_(context), kind_(kind) {}

 private:
  void Build();
  // When the fixated slice's patch is one the search barely finds in the reference frame
  // itself (PatchSelfConfidence), moves the fixation to the nearest slice whose patch it finds
  // surely (the agent's choice) or names that slice in a warning (the operator's).
  void HoldByASurePatch(std::uint64_t frame_index);
  // SSP over the swing after a lost lock (LostLockSsp): on the frame its run ends, the fixation
  // moves to the recommended slice when that is not the one in use.
  void SeeLostLock(const CapturedFrame& frame, bool lock_lost);

  ModeContext& context_;
  const AgentMode kind_;
  SliceChoice slice_choice_ = SliceChoice::kAgents;
  std::unique_ptr<FixationLoop> loop_;
  // The strategy the lost-lock SSP was built with (a settings change replaces the context's).
  std::shared_ptr<const SearchStrategy> ssp_strategy_;
  std::optional<LostLockSsp> lost_lock_ssp_;  // stored reference only (fixate, not follow)
  bool lock_lost_ = false;                    // the last frame's lock state, to log its changes
  bool trailing_ = false;                     // the last frame: lock held, the view off target
  std::uint64_t off_target_frames_ = 0;       // since the last off-target log line
  std::optional<std::uint64_t> last_off_target_log_;  // frame index of that line
  cv::Mat reference_frame_;                           // the frame the reference was taken from
  std::uint64_t reference_index_ = 0;                 // its index
  cv::Point2d reference_seen_at_{0, 0};               // [px] HeldView::seen_at of the view held
  // [deg] the angles it was seen through, where a lost lock sends the servos back; unknown
  // for a view taken up after a restart
  std::optional<ServoTargets> reference_angles_;
};

}  // namespace kapfix::agent
