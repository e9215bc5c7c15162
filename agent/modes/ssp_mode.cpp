#include "agent/modes/ssp_mode.hpp"

#include <spdlog/spdlog.h>

#include "agent/modes/report_messages.hpp"
#include "agent/modes/run_options.hpp"

namespace kapfix::agent {

void SspMode::Enter(const CapturedFrame& frame, const ServoTargets& current) {
  hold_ = current;
  window_.start_index = frame.index;
  strategy_ = context_.strategy();
  run_.emplace(context_.Plane(frame.image), *strategy_,
               MakeSliceSelectionOptions(context_.settings().search));
}

FrameOutcome SspMode::Process(const CapturedFrame& frame, const ServoTargets& /*current*/,
                              double /*dt_s*/) {
  if (frame.index != window_.start_index) run_->AddFrame(context_.Plane(frame.image));
  const bool done = window_.Reached(frame.index);
  const int used = run_->frames_used();
  if (done || used % kProgressEveryFrames == 0) {
    const SwingProgress progress = window_.Progress(used, done);
    const SliceSelection selection = run_->Result(progress.deadline_reached);
    context_.events().OnSliceReport(
        MakeSliceReport(selection, MakeSliceReportContext(context_.settings().search), progress));
    if (done) {
      // The recommended slice becomes the one in use; the operator confirms it (or picks
      // another) and starts fixating.
      run_.reset();
      context_.SetSliceRanking(selection.ranking);
      if (held_) {
        // The view fixated before SSP is held again until the operator confirms a slice
        // (select_slice): SSP alone never drops the lock.
        spdlog::info(
            "SSP finished after {} frames: slice {} recommended; fixating slice {} again until "
            "a slice is confirmed",
            used, selection.best_slice, held_->slice);
        Finish(ModeEnd{.fixate = std::move(held_), .hold = hold_, .resumed = std::nullopt});
      } else {
        context_.SetSlice(selection.best_slice);
        spdlog::info("SSP finished after {} frames: slice {} recommended", used,
                     selection.best_slice);
        Finish(ModeEnd{.fixate = std::nullopt, .hold = hold_, .resumed = std::nullopt});
      }
    }
  }
  return context_.Hold(AgentMode::kSsp, hold_);
}

}  // namespace kapfix::agent
