#include "agent/modes/mode_context.hpp"

#include <algorithm>
#include <stdexcept>

#include "agent/modes/run_options.hpp"
#include "common/control/controller_factory.hpp"
#include "common/control/servo_belief_controller.hpp"
#include "common/image/color_channel.hpp"
#include "common/selection/slice_geometry.hpp"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {
namespace {

// [jobs] a runner's own worker: a recording is written once per free swing.
constexpr std::size_t kOwnWorkerJobs = 4;

}  // namespace

ModeContext::ModeContext(std::shared_ptr<const AgentConfig> settings, ModeRunnerOptions options,
                         ModeEvents& events)
    : options_(std::move(options)), events_(events), settings_(std::move(settings)) {
  if (!options_.worker)
    options_.worker = std::make_shared<WorkQueue>("mode writer", kOwnWorkerJobs);
  slice_ = (settings_->search.slices + 1) / 2;
  Rebuild();
}

void ModeContext::Rebuild() {
  std::string error;
  std::shared_ptr<const SearchStrategy> strategy =
      MakeSearchStrategy(settings_->search.strategy, &error);
  if (!strategy) throw std::runtime_error("search: " + error);
  strategy_ = std::move(strategy);
  MakeLoop(FixationOptions::Reference::kStored);  // the controller too
}

std::unique_ptr<FixationLoop> ModeContext::MakeLoop(FixationOptions::Reference reference) const {
  const LensProfile& lens = settings_->active_lens();
  const LensCalibration calibration{lens.DegPerPxPan(), lens.DegPerPxTilt()};
  std::string error;
  std::unique_ptr<Controller> controller =
      MakeController(kapfix::v1::WordOf(settings_->gains.controller()), MakeGains(settings_->gains),
                     calibration, options_.predictive, &error);
  if (!controller) throw std::runtime_error("controller: " + error);
  // Only against a stored reference: the belief tells the candidates apart by how well their
  // views continue the swing, which a displacement from the previous frame (follow) is not.
  if (options_.servo_belief && reference == FixationOptions::Reference::kStored) {
    controller = std::make_unique<ServoBeliefController>(std::move(controller),
                                                         options_.servo_belief, calibration);
  }
  return std::make_unique<FixationLoop>(MakeFixationOptions(settings_->search, slice_, reference),
                                        strategy_, std::move(controller), calibration);
}

int ModeContext::ClampSlice(int slice) const {
  return std::clamp(slice, 1, settings_->search.slices);
}

cv::Mat ModeContext::Plane(const cv::Mat& frame_bgr) const {
  return ExtractChannel(frame_bgr, settings_->search.channel);
}

cv::Rect ModeContext::SlicePatchRect(cv::Size frame) const {
  return SlicePatch(frame, settings_->search.slices, slice_, settings_->search.patch_px);
}

FrameOutcome ModeContext::Hold(AgentMode mode, const ServoTargets& targets) const {
  FrameOutcome outcome;
  outcome.step.targets = targets;
  outcome.mode = mode;
  outcome.slice = slice_;
  outcome.slice_count = settings_->search.slices;
  return outcome;
}

}  // namespace kapfix::agent
