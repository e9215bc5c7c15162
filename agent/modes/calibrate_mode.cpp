#include "agent/modes/calibrate_mode.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <stdexcept>

#include "agent/modes/report_messages.hpp"
#include "agent/modes/run_options.hpp"

namespace kapfix::agent {
namespace {

// [px] each calibration move shifts the view by about this much at the lens's current deg/px:
// large against the matcher's noise, well inside its search range.
constexpr double kCalibrationSpanPx = 30.0;
constexpr int kCalibrationStepsPerSide = 5;

}  // namespace

void CalibrateMode::Enter(const CapturedFrame& frame, const ServoTargets& current) {
  hold_ = current;
  const AgentConfig& settings = context_.settings();
  const LensProfile& lens = settings.active_lens();
  CalibrationRunOptions o;
  o.span_deg = kCalibrationSpanPx * std::max(lens.DegPerPxPan(), lens.DegPerPxTilt());
  o.step_deg = o.span_deg / kCalibrationStepsPerSide;
  o.settle_frames = context_.options().actuation_delay_frames + 1;
  o.patch = context_.SlicePatchRect(context_.Plane(frame.image).size());
  o.sampling = settings.search.sampling;
  o.search = MakeSearchOptions(settings.search);
  o.park = current;
  strategy_ = context_.strategy();
  run_.emplace(o, *strategy_);
}

FrameOutcome CalibrateMode::Process(const CapturedFrame& frame, const ServoTargets& /*current*/,
                                    double /*dt_s*/) {
  FrameOutcome outcome = context_.Hold(AgentMode::kCalibrate, hold_);
  outcome.step.targets = run_->Step(context_.Plane(frame.image));
  const std::string lens = context_.settings().lens;  // a copy: the settings may be replaced
  if (!run_->finished()) {
    if (run_->moves_done() != progress_) {
      progress_ = run_->moves_done();
      context_.events().OnCalibrationReport(
          MakeCalibrationReport(lens, std::nullopt, std::nullopt, run_->moves_done(),
                                run_->moves_total(), false),
          std::nullopt);
    }
    return outcome;
  }
  std::optional<AxisCalibration> pan;
  std::optional<AxisCalibration> tilt;
  const std::optional<LensCalibration> applied = Fit(lens, &pan, &tilt);
  context_.events().OnCalibrationReport(
      MakeCalibrationReport(lens, pan, tilt, run_->moves_done(), run_->moves_total(), true),
      applied);
  run_.reset();
  Finish(ModeEnd{.fixate = std::nullopt, .hold = hold_, .resumed = std::nullopt});
  return outcome;
}

std::optional<LensCalibration> CalibrateMode::Fit(const std::string& lens,
                                                  std::optional<AxisCalibration>* pan,
                                                  std::optional<AxisCalibration>* tilt) {
  try {
    *pan = run_->FitPan();
    *tilt = run_->FitTilt();
  } catch (const std::invalid_argument& e) {
    spdlog::error("calibration failed, the lens keeps its deg/px: {}", e.what());
    return std::nullopt;
  }
  const LensCalibration fitted = LensCalibration::FromCalibrationMoves(**pan, **tilt);
  std::string error;
  if (!fitted.IsValid(&error)) {
    spdlog::error("calibration gave an unusable fit, the lens keeps its deg/px: {}", error);
    return std::nullopt;
  }
  // A new snapshot made the way the owner makes one; the owner's follows (RequestSettings).
  auto calibrated = std::make_shared<AgentConfig>(context_.settings());
  calibrated->ApplyLensCalibration(lens, fitted);
  context_.SetSettings(std::move(calibrated));
  spdlog::info(
      "calibrated lens {}: pan {:.5f} deg/px (residual {:.2f} px), tilt {:.5f} "
      "deg/px (residual {:.2f} px)",
      lens, fitted.pan_deg_per_px, (*pan)->residual_px, fitted.tilt_deg_per_px,
      (*tilt)->residual_px);
  return fitted;
}

}  // namespace kapfix::agent
