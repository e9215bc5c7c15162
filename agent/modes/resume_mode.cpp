#include "agent/modes/resume_mode.hpp"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <memory>
#include <string>

#include "agent/modes/run_options.hpp"
#include "common/matching/reference_patch.hpp"
#include "common/sampling/sample_set.hpp"

namespace kapfix::agent {
namespace {

// The whole-frame search of a resume: the hierarchical strategy, whatever the fixation
// uses, so a frame-wide window costs about what the exhaustive one does on ±range.
constexpr const char* kResumeStrategy = "pyr";

}  // namespace

FrameOutcome ResumeMode::Process(const CapturedFrame& frame, const ServoTargets& /*current*/,
                                 double /*dt_s*/) {
  FrameOutcome outcome = context_.Hold(AgentMode::kIdle, hold_);
  outcome.step.lock_lost = true;
  const SearchConfig& search = context_.settings().search;
  std::string error;
  const std::unique_ptr<SearchStrategy> strategy = MakeSearchStrategy(kResumeStrategy, &error);
  const cv::Mat stored = context_.Plane(reference_frame_);
  const cv::Mat plane = context_.Plane(frame.image);
  const FixationOptions fixation =
      MakeFixationOptions(search, context_.slice(), FixationOptions::Reference::kStored);
  if (strategy && stored.size() == plane.size() && stored.type() == plane.type()) {
    const cv::Rect patch = context_.SlicePatchRect(stored.size());
    const ReferencePatch reference(stored, SampleSet({patch}, search.sampling));
    SearchOptions wide = MakeSearchOptions(search);
    wide.axis = SearchAxis::kBoth;  // wherever the restart left the view
    wide.range = std::max(plane.cols, plane.rows);
    wide.origin = {0, 0};
    outcome.step.match = strategy->Search(reference, plane, wide);
  } else {
    frames_left_ = 0;  // another camera or frame size: the view cannot be compared
    if (error.empty()) {
      error = fmt::format("the stored reference is {}x{} px, the camera's frames {}x{} px",
                          stored.cols, stored.rows, plane.cols, plane.rows);
    }
  }
  const SearchResult& match = outcome.step.match;
  if (match.found && match.confidence >= fixation.lock_lost_confidence) {
    // Found: the stored view becomes the reference and the loop closes from where it is.
    spdlog::info(
        "resumed: the view of slice {} held before the restart found at ({}, {}) px, confidence "
        "{:.2f}; fixating it",
        context_.slice(), match.shift.x, match.shift.y, match.confidence);
    Finish(ModeEnd{.fixate = HeldView{.reference_frame = reference_frame_,
                                      .reference_index = frame.index,
                                      .slice = context_.slice(),
                                      .seek_from = match.shift,
                                      .seen_at = match.displacement},
                   .hold = hold_,
                   .resumed = true});
    return outcome;
  }
  if (match.found) best_confidence_ = std::max(best_confidence_, match.confidence);
  if (--frames_left_ > 0) return outcome;
  if (error.empty()) {
    error = fmt::format("best confidence {:.2f} in {} frames, below {:.2f}", best_confidence_,
                        kResumeFrames, fixation.lock_lost_confidence);
  }
  spdlog::warn(
      "not resumed: the view of slice {} held before the restart was not found ({}); the agent "
      "stays idle: run SSP or select a slice to fixate",
      context_.slice(), error);
  Finish(ModeEnd{.fixate = std::nullopt, .hold = hold_, .resumed = false});
  return outcome;
}

}  // namespace kapfix::agent
