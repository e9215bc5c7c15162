#include "common/evaluation/closed_loop_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

#include "common/analysis/statistics.hpp"
#include "common/control/controller_factory.hpp"
#include "common/control/servo_belief_controller.hpp"
#include "common/evaluation/free_swing_slice.hpp"

namespace kapfix {
namespace {

constexpr double kGrossErrorPx = 10;  // [px] a view error beyond this is gross (issue 9)

SimulatedPlatformOptions WorldPlatform(const ClosedLoopOptions& options) {
  SimulatedPlatformOptions platform = options.platform;
  options.world.ApplyTo(&platform);
  return platform;
}

PredictiveOptions EffectivePredictive(const ClosedLoopOptions& options) {
  PredictiveOptions predictive = options.predictive;
  if (predictive.predictor.lead_frames == 0) {
    // Capture t → command → Step (latency L: not yet) … → first frame showing it: t + 1 + L;
    // with a jittering latency, aimed at every delay it may take.
    const SimulatedServoOptions& pan = WorldPlatform(options).pan;
    predictive.predictor.lead_frames = 1 + pan.latency_frames;
    predictive.lead_jitter_frames = std::max(0, pan.latency_max_frames - pan.latency_frames);
  }
  return predictive;
}

}  // namespace

bool ClosedLoopOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!world.IsValid(error)) return false;
  if (!WorldPlatform(*this).IsValid(error) || !fixation.IsValid(error) || !gains.IsValid(error)) {
    return false;
  }
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
  if (start == Start::kAfterSsp && ssp_frames < 2) {
    return fail("SSP before fixation needs ≥ 2 frames, got " + std::to_string(ssp_frames));
  }
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

namespace {

// The online deg/px estimate of the predictive controller (pan axis) against the truth; NaN
// without a predictive controller.
void FillCalibrationEstimate(const PredictiveController* predictive, double px_per_deg,
                             ClosedLoopFigures* figures) {
  figures->deg_per_px_estimate_ratio = std::numeric_limits<double>::quiet_NaN();
  figures->deg_per_px_estimate_sigma = std::numeric_limits<double>::quiet_NaN();
  if (!predictive) return;
  const DegPerPxEstimator& estimator = predictive->pan_estimator();
  figures->deg_per_px_estimate_ratio = estimator.estimate_deg_per_px() * px_per_deg;
  figures->deg_per_px_estimate_sigma = estimator.relative_sigma();
  figures->deg_per_px_estimate_trusted = estimator.trusted();
}

// Counts what the loop said about its gross frames (issue 9's honest lock): a gross frame is
// silent when the loop claimed to hold the view (off_target false).
struct LockHonesty {
  int gross = 0, silent_gross = 0, gross_lock_held = 0, off_target_frames = 0;

  void Add(double view_error, bool lock_lost, bool off_target, ClosedLoopFigures* figures) {
    figures->lock_lost.push_back(lock_lost);
    figures->off_target.push_back(off_target);
    off_target_frames += off_target ? 1 : 0;
    if (view_error > kGrossErrorPx) {
      ++gross;
      silent_gross += off_target ? 0 : 1;
      gross_lock_held += lock_lost ? 0 : 1;
    }
  }
  // As shares [%] of all `frames`.
  void Finish(double frames, ClosedLoopFigures* figures) const {
    figures->gross_pct = 100.0 * gross / frames;
    figures->silent_gross_pct = 100.0 * silent_gross / frames;
    figures->gross_lock_held_pct = 100.0 * gross_lock_held / frames;
    figures->off_target_pct = 100.0 * off_target_frames / frames;
  }
};

// [deg] `target` as far as the servo reaches from `previous` in one command: within `step` of
// it and within [low, high].
double ServoReach(double target, double previous, double low, double high, double step) {
  return std::clamp(std::clamp(target, previous - step, previous + step), low, high);
}

}  // namespace

ClosedLoopFigures EvaluateClosedLoop(const cv::Mat& scene_bgr, const ClosedLoopOptions& options,
                                     const std::function<void(int, int)>& progress) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("EvaluateClosedLoop: " + error);
  const SimulatedPlatformOptions platform_options = WorldPlatform(options);
  SimulatedPlatform platform(scene_bgr, platform_options);
  const double deg_per_px =
      options.calibration_scale * options.world.calibration_error / platform_options.px_per_deg;
  const LensCalibration calibration{deg_per_px, deg_per_px};
  std::unique_ptr<Controller> controller = MakeController(
      options.controller, options.gains, calibration, EffectivePredictive(options), &error);
  const auto* predictive = dynamic_cast<const PredictiveController*>(controller.get());
  const std::shared_ptr<const SearchStrategy> strategy =
      MakeSearchStrategy(options.strategy, &error);
  FixationOptions fixation = options.fixation;
  if (options.start == ClosedLoopOptions::Start::kAfterSsp) {
    fixation.slice = FreeSwingSlice(platform, fixation, *strategy, options.ssp_frames);
    platform.Step();
  }
  // What the controller believes the servos show: built from the commands sent, never from
  // the servos' true output angles (those stay the simulation's), and resolved from each
  // frame's measurement when the latency jitters (ServoBelief).
  const ServoTargets initial{platform_options.pan.initial_deg, platform_options.tilt.initial_deg};
  const auto belief = std::make_shared<ServoBelief>(ServoBeliefOptions{
      1 + platform_options.pan.latency_frames,
      1 + std::max(platform_options.pan.latency_frames, platform_options.pan.latency_max_frames),
      initial});
  FixationLoop loop(
      fixation, strategy,
      std::make_unique<ServoBeliefController>(std::move(controller), belief, calibration),
      calibration);
  // The driver also keeps each command within the servo's rated speed of the previous one,
  // so that the command is what the servo can reach: otherwise the controller's belief
  // (the command) and the servo's true angle part whenever the rate limit bites, and a loop
  // acting on that belief feeds its own error back.
  ServoTargets last_sent = initial;
  int last_sent_frame = -1;
  const auto command = [&](int frame, const ServoTargets& targets) {
    const int frames_since = last_sent_frame < 0 ? 1 : frame - last_sent_frame;
    const ServoTargets clamped{
        ServoReach(targets.pan_deg, last_sent.pan_deg, platform_options.pan.min_deg,
                   platform_options.pan.max_deg,
                   platform_options.pan.rate_limit_deg_per_frame * frames_since),
        ServoReach(targets.tilt_deg, last_sent.tilt_deg, platform_options.tilt.min_deg,
                   platform_options.tilt.max_deg,
                   platform_options.tilt.rate_limit_deg_per_frame * frames_since)};
    platform.CommandPan(clamped.pan_deg);
    platform.CommandTilt(clamped.tilt_deg);
    belief->Sent(frame, clamped);
    last_sent = clamped;
    last_sent_frame = frame;
  };
  // Frame 0 is the reference, and also the loop's first measurement (displacement 0): the
  // controller's history starts there, as the agent's does when it fixates mid-stream.
  const cv::Point2d held = platform.ViewOffset();  // [px] the reference's view
  {
    const SimulatedFrame reference = platform.CaptureFrame();
    loop.SetReference(reference.image);
    const FixationLoop::Step step =
        loop.Process(reference.image, belief->Expose(reference.frame), options.frame_period_s);
    command(reference.frame, step.targets);
  }

  ClosedLoopFigures figures;
  figures.frames = options.frames;
  figures.slice = fixation.slice;
  std::vector<double> loop_us;
  loop_us.reserve(static_cast<std::size_t>(options.frames));
  std::vector<double> errors;
  errors.reserve(static_cast<std::size_t>(options.frames));
  double sum_x = 0, sum_y = 0, sum_open = 0, total_us = 0, sum_miss = 0, sum_confidence = 0;
  int measured = 0;
  int lost = 0, predicting = 0, dropped = 0, missed = 0;
  bool lock_lost = false, off_target = false;
  LockHonesty honesty;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (int i = 0; i < options.frames; ++i) {
    platform.Step();
    const SimulatedFrame frame = platform.CaptureFrame();
    const cv::Point2d offset = platform.ViewOffset() - held;  // of the frame just captured
    const cv::Point2d open = platform.OpenLoopOffset();
    figures.view_offsets.push_back(offset);
    figures.angles.push_back({frame.pan_deg, frame.tilt_deg});
    sum_x += offset.x * offset.x;
    sum_y += offset.y * offset.y;
    sum_open += open.dot(open);
    const double view_error = std::hypot(offset.x, offset.y);
    errors.push_back(view_error);
    if (platform.FrameDropped(frame.frame)) {
      // Lost by the camera: nothing is measured or commanded; the lock state stands.
      ++dropped;
      ++missed;
      figures.measured_x.push_back(nan);
      figures.measured_y.push_back(nan);
      figures.believed.push_back({nan, nan});
      figures.commanded.push_back({nan, nan});
      lost += lock_lost ? 1 : 0;
      honesty.Add(view_error, lock_lost, off_target, &figures);
      if (progress) progress(i + 1, options.frames);
      continue;
    }
    const FixationLoop::Step step = loop.Process(frame.image, belief->Expose(frame.frame),
                                                 options.frame_period_s * (1 + missed));
    missed = 0;
    figures.believed.push_back(belief->Believed());
    command(frame.frame, step.targets);
    figures.commanded.push_back(last_sent);
    lock_lost = step.lock_lost;
    off_target = step.off_target;
    honesty.Add(view_error, lock_lost, off_target, &figures);

    if (step.match.found) {
      // A perfect match measures −ViewOffset (the content moves against the view).
      const cv::Point2d miss = step.match.displacement + offset;
      sum_miss += miss.dot(miss);
      sum_confidence += step.match.confidence;
      ++measured;
    }
    figures.measured_x.push_back(step.match.found ? step.match.displacement.x : nan);
    figures.measured_y.push_back(step.match.found ? step.match.displacement.y : nan);
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
  figures.p95_error_px = Percentile(errors, 95.0);
  figures.measurement_rms_px = measured > 0 ? std::sqrt(sum_miss / measured) : nan;
  figures.confidence_loss = measured > 0 ? 1.0 - sum_confidence / measured : nan;
  honesty.Finish(n, &figures);
  figures.dropped_pct = 100.0 * dropped / n;
  figures.predicting_pct = 100.0 * predicting / n;
  FillCalibrationEstimate(predictive, platform_options.px_per_deg, &figures);
  figures.fps = total_us > 0 ? n / (total_us * 1e-6) : 0.0;
  figures.loop_latency_p50_ms = loop_us.empty() ? 0.0 : Percentile(loop_us, 50.0) / 1000.0;
  figures.loop_latency_p99_ms = loop_us.empty() ? 0.0 : Percentile(loop_us, 99.0) / 1000.0;
  return figures;
}

}  // namespace kapfix
