#include "common/evaluation/closed_loop_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <stdexcept>
#include <vector>

#include "common/analysis/statistics.hpp"
#include "common/control/controller_factory.hpp"
#include "common/control/servo_belief_controller.hpp"
#include "common/evaluation/aim_floor.hpp"
#include "common/evaluation/free_swing_slice.hpp"
#include "common/fixation/patch_self_confidence.hpp"
#include "common/image/color_channel.hpp"
#include "common/selection/lost_lock_ssp.hpp"
#include "common/sim/scene_camera.hpp"

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
  if (ssp_after_lost_frames < 0) {
    return fail("SSP after a lost lock: the wait must be ≥ 0 frames, got " +
                std::to_string(ssp_after_lost_frames));
  }
  if ((start == Start::kAfterSsp || ssp_after_lost_frames > 0) && ssp_frames < 2) {
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

  // `seen`: the camera delivered the frame, so the loop's claim is about it; a dropped frame
  // keeps the previous claim in the trace, but no claim was made for it.
  void Add(double view_error, bool lock_lost, bool off_target, bool seen,
           ClosedLoopFigures* figures) {
    figures->lock_lost.push_back(lock_lost);
    figures->off_target.push_back(off_target);
    off_target_frames += off_target ? 1 : 0;
    if (view_error > kGrossErrorPx) {
      ++gross;
      silent_gross += off_target || !seen ? 0 : 1;
      gross_lock_held += lock_lost || !seen ? 0 : 1;
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

namespace {

// One closed-loop flight: the simulated platform, what the controller believes the servos
// show, the fixation loop, and the figures' accumulators. Built once per EvaluateClosedLoop;
// the steps run in the order of the original single function, so the random draws keep their
// order.
class ClosedLoopRun {
 public:
  // `options` must be IsValid and outlive the run.
  ClosedLoopRun(const cv::Mat& scene_bgr, const ClosedLoopOptions& options)
      : options_(options),
        platform_options_(WorldPlatform(options)),
        platform_(scene_bgr, platform_options_),
        calibration_(Calibration(options, platform_options_)),
        initial_{platform_options_.pan.initial_deg, platform_options_.tilt.initial_deg},
        last_sent_(initial_) {
    SetUp();
  }

  // Frame 0 is the reference, and also the loop's first measurement (displacement 0): the
  // controller's history starts there, as the agent's does when it fixates mid-stream.
  void FixateOnReference() {
    held_ = platform_.ViewOffset();
    const SimulatedFrame reference = platform_.CaptureFrame();
    const ServoTargets seen_through = belief_->Expose(reference.frame);
    reference_image_ = reference.image;
    reference_seen_through_ = seen_through;
    loop_->SetReference(reference.image, seen_through);
    reference_roll_rad_ = RollRad(reference.frame);
    patch_centre_ = PatchCentre();
    const FixationLoop::Step step =
        loop_->Process(reference.image, seen_through, options_.frame_period_s);
    Command(reference.frame, step.targets);
  }

  // Steps the platform one frame, captures it, and lets the loop measure and command.
  void StepFrame() {
    platform_.Step();
    const SimulatedFrame frame = platform_.CaptureFrame();
    const cv::Point2d offset = platform_.ViewOffset() - held_;  // of the frame just captured
    const double view_error = RecordViewError(frame, offset);
    if (platform_.FrameDropped(frame.frame)) {
      RecordDroppedFrame(view_error);
      return;
    }
    const FixationLoop::Step step = loop_->Process(frame.image, belief_->Expose(frame.frame),
                                                   options_.frame_period_s * (1 + missed_));
    missed_ = 0;
    figures_.believed.push_back(belief_->Believed());
    Command(frame.frame, step.targets);
    figures_.commanded.push_back(last_sent_);
    lock_lost_ = step.lock_lost;
    off_target_ = step.off_target;
    honesty_.Add(view_error, lock_lost_, off_target_, /*seen=*/true, &figures_);
    RecordMeasurement(step, offset, frame.frame);
    SeeLostLock(frame.image, step.lock_lost);
  }

  // The flight's figures from the accumulators; call once, after the last StepFrame.
  ClosedLoopFigures Figures() {
    const double n = options_.frames;
    figures_.rms_error_x_px = std::sqrt(sum_x_ / n);
    figures_.rms_error_y_px = std::sqrt(sum_y_ / n);
    figures_.rms_error_px = std::sqrt((sum_x_ + sum_y_) / n);
    figures_.open_loop_rms_px = std::sqrt(sum_open_ / n);
    const SimulatedServoOptions& pan = platform_options_.pan;
    figures_.aim_floor_rms_px =
        AimFloorRms(figures_.open_offsets, 1 + pan.latency_frames,
                    std::max(0, pan.latency_max_frames - pan.latency_frames));
    figures_.lock_lost_pct = 100.0 * lost_ / n;
    figures_.p95_error_px = Percentile(errors_, 95.0);
    figures_.measurement_rms_px = measured_ > 0 ? std::sqrt(sum_miss_ / measured_) : kNan;
    figures_.slice_miss_rms_px = measured_ > 0 ? std::sqrt(sum_slice_miss_ / measured_) : kNan;
    figures_.confidence_loss = measured_ > 0 ? 1.0 - sum_confidence_ / measured_ : kNan;
    honesty_.Finish(n, &figures_);
    figures_.dropped_pct = 100.0 * dropped_ / n;
    figures_.predicting_pct = 100.0 * predicting_ / n;
    FillCalibrationEstimate(predictive_, platform_options_.px_per_deg, &figures_);
    figures_.fps = total_us_ > 0 ? n / (total_us_ * 1e-6) : 0.0;
    figures_.loop_latency_p50_ms = loop_us_.empty() ? 0.0 : Percentile(loop_us_, 50.0) / 1000.0;
    figures_.loop_latency_p99_ms = loop_us_.empty() ? 0.0 : Percentile(loop_us_, 99.0) / 1000.0;
    return figures_;
  }

 private:
  static constexpr double kNan = std::numeric_limits<double>::quiet_NaN();

  static LensCalibration Calibration(const ClosedLoopOptions& options,
                                     const SimulatedPlatformOptions& platform_options) {
    const double deg_per_px =
        options.calibration_scale * options.world.calibration_error / platform_options.px_per_deg;
    return LensCalibration{deg_per_px, deg_per_px};
  }

  // [px] the patch's centre from the frame's centre.
  cv::Point2d PatchCentre() const {
    const cv::Rect patch = loop_->patch();
    return {patch.x + (patch.width - 1) / 2.0 - (reference_image_.cols - 1) / 2.0,
            patch.y + (patch.height - 1) / 2.0 - (reference_image_.rows - 1) / 2.0};
  }

  // A loop on `fixation`'s slice with a new controller, acting through the one servo belief.
  void MakeLoop(const FixationOptions& fixation) {
    std::string error;
    std::unique_ptr<Controller> controller = MakeController(
        options_.controller, options_.gains, calibration_, EffectivePredictive(options_), &error);
    predictive_ = dynamic_cast<const PredictiveController*>(controller.get());
    loop_ = std::make_unique<FixationLoop>(
        fixation, strategy_,
        std::make_unique<ServoBeliefController>(std::move(controller), belief_, calibration_),
        calibration_);
  }

  // The agent's SSP after a lost lock (FixateMode): on the frame its run ends, the same
  // reference is held by the next slice of SSP's ranking whose patch the search finds surely
  // in it, the slice in use left out.
  void SeeLostLock(const cv::Mat& frame_bgr, bool lock_lost) {
    if (!lost_lock_ssp_) return;
    const std::optional<SliceSelection> selection = lost_lock_ssp_->See(
        lock_lost, [&] { return ExtractChannel(frame_bgr, fixation_.channel); });
    if (!selection) return;
    const std::optional<int> next = ConfidentSliceBesides(reference_image_, selection->ranking,
                                                          fixation_.slice, fixation_, *strategy_);
    if (!next) return;
    fixation_.slice = *next;
    const std::optional<ServoTargets> centre = loop_->swing_centre();
    MakeLoop(fixation_);
    loop_->SetReference(reference_image_, reference_seen_through_);
    if (centre) loop_->KeepSwingCentre(*centre);
    patch_centre_ = PatchCentre();
    figures_.slice = fixation_.slice;
    ++figures_.slices_after_lost_lock;
  }

  // Controller, search strategy, slice (after SSP's free swing if asked), belief and loop,
  // in this order.
  void SetUp() {
    std::string error;
    strategy_ = MakeSearchStrategy(options_.strategy, &error);
    const std::shared_ptr<const SearchStrategy>& strategy = strategy_;
    FixationOptions fixation = options_.fixation;
    if (options_.start == ClosedLoopOptions::Start::kAfterSsp) {
      const std::vector<int> ranking =
          FreeSwingRanking(platform_, fixation, *strategy, options_.ssp_frames);
      platform_.Step();
      // The patch is cut from the frame that becomes the reference, and a slice SSP liked over
      // the swing may land on a weak part of the scene there: the agent's fixate then takes
      // SSP's next slice whose patch passes (FixateMode::HoldByASurePatch), as here.
      fixation.slice = ConfidentSlice(platform_.Capture(), ranking, fixation, *strategy);
    } else {
      if (options_.start == ClosedLoopOptions::Start::kMoving) {
        platform_.Step();  // the servos hold; the swing (and its blur) is under way
      }
      // As the agent's fixate: the agent's slice's patch, when the search barely finds it in
      // the frame that becomes the reference, gives way to the nearest slice whose it finds
      // surely (FixateMode::HoldByASurePatch).
      if (!options_.keep_slice) {
        const cv::Mat reference = platform_.Capture();
        const double least = fixation.lock_regain_confidence;
        if (PatchSelfConfidence(reference, fixation.slice, fixation, *strategy) < least) {
          fixation.slice =
              NearestConfidentSlice(PatchSelfConfidences(reference, fixation, *strategy),
                                    fixation.slice, least)
                  .value_or(fixation.slice);
        }
      }
    }
    // What the controller believes the servos show: built from the commands sent, never from
    // the servos' true output angles (those stay the simulation's), and resolved from each
    // frame's measurement when the latency jitters (ServoBelief). It knows the servos' specs
    // (latency, speed, play), as the agent does for its simulated servos.
    const SimulatedServoOptions& pan = platform_options_.pan;
    const SimulatedServoOptions& tilt = platform_options_.tilt;
    belief_ = std::make_shared<ServoBelief>(
        ServoBeliefOptions{1 + pan.latency_frames,
                           1 + std::max(pan.latency_frames, pan.latency_max_frames),
                           initial_,
                           {pan.rate_limit_deg_per_frame, tilt.rate_limit_deg_per_frame},
                           {pan.backlash_deg, tilt.backlash_deg}});
    fixation_ = fixation;
    MakeLoop(fixation);
    if (options_.ssp_after_lost_frames > 0) {
      lost_lock_ssp_.emplace(*strategy_,
                             LostLockSspOptions{options_.ssp_after_lost_frames, options_.ssp_frames,
                                                SliceSelectionOptionsFor(fixation)});
    }
    figures_.frames = options_.frames;
    figures_.slice = fixation.slice;
    loop_us_.reserve(static_cast<std::size_t>(options_.frames));
    errors_.reserve(static_cast<std::size_t>(options_.frames));
  }

  // The driver also keeps each command within the servo's rated speed of the previous one,
  // so that the command is what the servo can reach: otherwise the controller's belief
  // (the command) and the servo's true angle part whenever the rate limit bites, and a loop
  // acting on that belief feeds its own error back.
  void Command(int frame, const ServoTargets& targets) {
    const int frames_since = last_sent_frame_ < 0 ? 1 : frame - last_sent_frame_;
    const SimulatedServoOptions& pan = platform_options_.pan;
    const SimulatedServoOptions& tilt = platform_options_.tilt;
    const ServoTargets clamped{
        ServoReach(targets.pan_deg, last_sent_.pan_deg, pan.min_deg, pan.max_deg,
                   pan.rate_limit_deg_per_frame * frames_since),
        ServoReach(targets.tilt_deg, last_sent_.tilt_deg, tilt.min_deg, tilt.max_deg,
                   tilt.rate_limit_deg_per_frame * frames_since)};
    platform_.CommandPan(clamped.pan_deg);
    platform_.CommandTilt(clamped.tilt_deg);
    belief_->Sent(frame, clamped);
    last_sent_ = clamped;
    last_sent_frame_ = frame;
  }

  // The truth of the frame just captured (view offset [px], servo angles); returns its view
  // error [px].
  double RecordViewError(const SimulatedFrame& frame, const cv::Point2d& offset) {
    const cv::Point2d open = platform_.OpenLoopOffset();
    figures_.view_offsets.push_back(offset);
    figures_.open_offsets.push_back(open);
    figures_.angles.push_back({frame.pan_deg, frame.tilt_deg});
    sum_x_ += offset.x * offset.x;
    sum_y_ += offset.y * offset.y;
    sum_open_ += open.dot(open);
    const double view_error = std::hypot(offset.x, offset.y);
    errors_.push_back(view_error);
    return view_error;
  }

  // Lost by the camera: nothing is measured or commanded; the lock state stands.
  void RecordDroppedFrame(double view_error) {
    ++dropped_;
    ++missed_;
    figures_.measured_x.push_back(kNan);
    figures_.measured_y.push_back(kNan);
    figures_.confidence.push_back(kNan);
    figures_.believed.push_back({kNan, kNan});
    figures_.commanded.push_back({kNan, kNan});
    figures_.pan_forecast.push_back({kNan, kNan, kNan, kNan});
    figures_.tilt_forecast.push_back({kNan, kNan, kNan, kNan});
    figures_.roll_read_deg.push_back(kNan);
    figures_.roll_true_deg.push_back(kNan);
    lost_ += lock_lost_ ? 1 : 0;
    honesty_.Add(view_error, lock_lost_, off_target_, /*seen=*/false, &figures_);
  }

  // [rad] the camera's roll at `frame`.
  double RollRad(int frame) const {
    return SceneRollDeg(platform_options_.camera, frame) * std::numbers::pi / 180.0;
  }

  // [px] What a perfect match of the fixated patch measures at `frame` whose view is `offset`
  // from the reference's: the scene point under the patch centre u (from the frame centre)
  // in the reference, C + L_ref + R(roll_ref)·u, seen in this frame at R(−roll)·(L_ref − L +
  // R(roll_ref)·u) from the centre (SceneCamera's warp without its keystone), less u. −offset
  // when there is no roll.
  cv::Point2d SliceTruth(const cv::Point2d& offset, int frame) const {
    const auto rotate = [](double a, const cv::Point2d& v) {
      return cv::Point2d(std::cos(a) * v.x - std::sin(a) * v.y,
                         std::sin(a) * v.x + std::cos(a) * v.y);
    };
    return rotate(-RollRad(frame), rotate(reference_roll_rad_, patch_centre_) - offset) -
           patch_centre_;
  }

  // What the matcher measured against the truth `offset` [px] (and the slice's own truth at
  // `frame`), the lock, the forecast share and the loop's time.
  void RecordMeasurement(const FixationLoop::Step& step, const cv::Point2d& offset, int frame) {
    if (step.match.found) {
      // A perfect match measures −ViewOffset (the content moves against the view).
      const cv::Point2d miss = step.match.displacement + offset;
      sum_miss_ += miss.dot(miss);
      const cv::Point2d slice_miss = step.match.displacement - SliceTruth(offset, frame);
      sum_slice_miss_ += slice_miss.dot(slice_miss);
      sum_confidence_ += step.match.confidence;
      ++measured_;
    }
    figures_.measured_x.push_back(step.match.found ? step.match.displacement.x : kNan);
    figures_.measured_y.push_back(step.match.found ? step.match.displacement.y : kNan);
    figures_.confidence.push_back(step.match.confidence);
    figures_.roll_read_deg.push_back(step.roll_deg);
    // The camera's roll turns the content the other way (SliceTruth).
    figures_.roll_true_deg.push_back(-(RollRad(frame) - reference_roll_rad_) * 180 /
                                     std::numbers::pi);
    lost_ += step.lock_lost ? 1 : 0;
    if (predictive_ && (predictive_->predicting_pan() || predictive_->predicting_tilt())) {
      ++predicting_;
    }
    figures_.pan_forecast.push_back(AxisForecast(0));
    figures_.tilt_forecast.push_back(AxisForecast(1));
    loop_us_.push_back(step.loop_us);
    total_us_ += step.loop_us;
  }

  // `axis`: 0 pan, 1 tilt.
  ClosedLoopFigures::AxisForecast AxisForecast(int axis) const {
    if (!predictive_) return {kNan, kNan, kNan, kNan};
    const bool pan = axis == 0;
    const bool predicting = pan ? predictive_->predicting_pan() : predictive_->predicting_tilt();
    const SwingPredictor& predictor =
        pan ? predictive_->pan_predictor() : predictive_->tilt_predictor();
    const auto deg_per_px = [pan](const LensCalibration& c) {
      return pan ? c.pan_deg_per_px : c.tilt_deg_per_px;
    };
    return {predicting ? static_cast<double>(predictor.chosen()) : 0.0,
            pan ? predictive_->pan_forecast_weight() : predictive_->tilt_forecast_weight(),
            deg_per_px(predictive_->calibration()) * platform_options_.px_per_deg,
            deg_per_px(belief_->Scaled(calibration_)) * platform_options_.px_per_deg};
  }

  const ClosedLoopOptions& options_;
  const SimulatedPlatformOptions platform_options_;
  SimulatedPlatform platform_;
  const LensCalibration calibration_;
  const ServoTargets initial_;
  const PredictiveController* predictive_ = nullptr;  // owned by loop_; null unless predictive
  std::shared_ptr<ServoBelief> belief_;
  std::shared_ptr<const SearchStrategy> strategy_;
  FixationOptions fixation_;  // the loop's, its slice the one in use
  std::unique_ptr<FixationLoop> loop_;
  std::optional<LostLockSsp> lost_lock_ssp_;
  cv::Mat reference_image_;              // the frame the reference was taken from
  ServoTargets reference_seen_through_;  // [deg] the angles the loop believes it was seen through
  ServoTargets last_sent_;
  int last_sent_frame_ = -1;
  cv::Point2d held_;               // [px] the reference's view
  double reference_roll_rad_ = 0;  // [rad] the camera's roll in the reference frame
  cv::Point2d patch_centre_;       // [px] the patch's centre from the frame's centre

  ClosedLoopFigures figures_;
  std::vector<double> loop_us_;  // [µs] per measured frame
  std::vector<double> errors_;   // [px] view error per frame
  double sum_x_ = 0, sum_y_ = 0, sum_open_ = 0, total_us_ = 0, sum_miss_ = 0, sum_confidence_ = 0;
  double sum_slice_miss_ = 0;
  int measured_ = 0, lost_ = 0, predicting_ = 0, dropped_ = 0, missed_ = 0;
  bool lock_lost_ = false, off_target_ = false;
  LockHonesty honesty_;
};

}  // namespace

ClosedLoopFigures EvaluateClosedLoop(const cv::Mat& scene_bgr, const ClosedLoopOptions& options,
                                     const std::function<void(int, int)>& progress) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument("EvaluateClosedLoop: " + error);
  ClosedLoopRun run(scene_bgr, options);
  run.FixateOnReference();
  for (int i = 0; i < options.frames; ++i) {
    run.StepFrame();
    if (progress) progress(i + 1, options.frames);
  }
  return run.Figures();
}

}  // namespace kapfix
