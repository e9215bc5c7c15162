#include "common/evaluation/closed_loop_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "common/analysis/statistics.hpp"
#include "common/control/controller_factory.hpp"

namespace kapfix {
namespace {

PredictiveOptions EffectivePredictive(const ClosedLoopOptions& options) {
  PredictiveOptions predictive = options.predictive;
  if (predictive.predictor.lead_frames == 0) {
    // Capture t → command → Step (latency L: not yet) … → first frame showing it: t + 1 + L.
    predictive.predictor.lead_frames = 1 + options.platform.pan.latency_frames;
  }
  return predictive;
}

}  // namespace

bool ClosedLoopOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!platform.IsValid(error) || !fixation.IsValid(error) || !gains.IsValid(error)) return false;
  if (!EffectivePredictive(*this).IsValid(error)) return false;
  std::string reason;
  if (!MakeSearchStrategy(strategy, &reason)) return fail(reason);
  if (std::find(ControllerNames().begin(), ControllerNames().end(), controller) ==
      ControllerNames().end()) {
    return fail("unknown controller '" + controller + "' (p, pid or predictive)");
  }
  if (!std::isfinite(calibration_scale) || calibration_scale <= 0) {
    return fail("calibration scale must be > 0, got " + std::to_string(calibration_scale));
  }
  if (frames < 1) return fail("closed loop needs ≥ 1 frame, got " + std::to_string(frames));
  if (!std::isfinite(frame_period_s) || frame_period_s <= 0) {
    return fail("frame period must be > 0 s, got " + std::to_string(frame_period_s));
  }
  return true;
}

ClosedLoopOptions ClosedLoopOptions::ForMotion(SimulatedPlatformOptions::Motion motion) {
  ClosedLoopOptions options;
  options.platform.motion = motion;
  if (motion == SimulatedPlatformOptions::Motion::kBoat) {
    options.fixation.search.axis = SearchAxis::kY;
    options.predictive.predictor.order = 8;
    options.predictive.predictor.window_frames = 160;
  }
  return options;
}

ClosedLoopFigures EvaluateClosedLoop(const cv::Mat& scene_bgr, const ClosedLoopOptions& options,
                                     const std::function<void(int, int)>& progress) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("EvaluateClosedLoop: " + error);
  SimulatedPlatform platform(scene_bgr, options.platform);
  const double deg_per_px = options.calibration_scale / options.platform.px_per_deg;
  const LensCalibration calibration{deg_per_px, deg_per_px};
  std::unique_ptr<Controller> controller = MakeController(
      options.controller, options.gains, calibration, EffectivePredictive(options), &error);
  const auto* predictive = dynamic_cast<const PredictiveController*>(controller.get());
  FixationLoop loop(options.fixation, MakeSearchStrategy(options.strategy, &error),
                    std::move(controller), calibration);
  // Frame 0 is the reference, and also the loop's first measurement (displacement 0): the
  // controller's history starts there, as the agent's does when it fixates mid-stream.
  {
    const SimulatedFrame reference = platform.CaptureFrame();
    loop.SetReference(reference.image);
    const FixationLoop::Step step = loop.Process(
        reference.image, {reference.pan_deg, reference.tilt_deg}, options.frame_period_s);
    platform.CommandPan(step.targets.pan_deg);
    platform.CommandTilt(step.targets.tilt_deg);
  }

  ClosedLoopFigures figures;
  figures.frames = options.frames;
  std::vector<double> loop_us;
  loop_us.reserve(static_cast<std::size_t>(options.frames));
  double sum_x = 0, sum_y = 0, sum_open = 0, total_us = 0;
  int lost = 0, predicting = 0;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < options.frames; ++i) {
    platform.Step();
    const SimulatedFrame frame = platform.CaptureFrame();
    const ServoTargets seen_through{frame.pan_deg, frame.tilt_deg};
    const FixationLoop::Step step = loop.Process(frame.image, seen_through, options.frame_period_s);
    platform.CommandPan(step.targets.pan_deg);
    platform.CommandTilt(step.targets.tilt_deg);

    const cv::Point2d offset = platform.ViewOffset();  // of the frame just processed
    const cv::Point2d open = platform.OpenLoopOffset();
    figures.view_offsets.push_back(offset);
    figures.angles.push_back(seen_through);
    figures.measured_x.push_back(step.match.found ? step.match.displacement.x : nan);
    figures.measured_y.push_back(step.match.found ? step.match.displacement.y : nan);
    sum_x += offset.x * offset.x;
    sum_y += offset.y * offset.y;
    sum_open += open.dot(open);
    lost += step.lock_lost ? 1 : 0;
    if (predictive && (predictive->predicting_pan() || predictive->predicting_tilt())) {
      ++predicting;
    }
    loop_us.push_back(step.loop_us);
    total_us += step.loop_us;
    if (progress) progress(i + 1, options.frames);
  }
  const double n = options.frames;
  figures.rms_error_x_px = std::sqrt(sum_x / n);
  figures.rms_error_y_px = std::sqrt(sum_y / n);
  figures.rms_error_px = std::sqrt((sum_x + sum_y) / n);
  figures.open_loop_rms_px = std::sqrt(sum_open / n);
  figures.lock_lost_pct = 100.0 * lost / n;
  figures.predicting_pct = 100.0 * predicting / n;
  figures.fps = total_us > 0 ? n / (total_us * 1e-6) : 0.0;
  figures.loop_latency_p50_ms = loop_us.empty() ? 0.0 : Percentile(loop_us, 50.0) / 1000.0;
  figures.loop_latency_p99_ms = loop_us.empty() ? 0.0 : Percentile(loop_us, 99.0) / 1000.0;
  return figures;
}

}  // namespace kapfix
