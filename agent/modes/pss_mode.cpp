#include "agent/modes/pss_mode.hpp"

#include <spdlog/spdlog.h>

#include "agent/modes/report_messages.hpp"
#include "agent/modes/run_options.hpp"

namespace kapfix::agent {

void PssMode::Enter(const CapturedFrame& frame, const ServoTargets& current) {
  hold_ = current;
  window_.start_index = frame.index;
  const cv::Mat plane = context_.Plane(frame.image);
  strategy_ = context_.strategy();
  run_.emplace(plane, *strategy_,
               MakePatchSizeSelectionOptions(context_.settings().search, plane.size()));
}

FrameOutcome PssMode::Process(const CapturedFrame& frame, const ServoTargets& /*current*/,
                              double /*dt_s*/) {
  if (frame.index != window_.start_index) run_->AddFrame(context_.Plane(frame.image));
  const bool done = window_.Reached(frame.index);
  const int used = run_->frames_used();
  if (done || used % kProgressEveryFrames == 0) {
    const SwingProgress progress = window_.Progress(used, done);
    const PatchSizeSelection selection = run_->Result();
    context_.events().OnPssReport(MakePssReport(selection, run_->graphs(), progress));
    if (done) {
      run_.reset();
      spdlog::info("PSS finished after {} frames: {} px recommended", used, selection.best_size);
      Finish(ModeEnd{.fixate = std::nullopt, .hold = hold_, .resumed = std::nullopt});
    }
  }
  return context_.Hold(AgentMode::kPss, hold_);
}

}  // namespace kapfix::agent
