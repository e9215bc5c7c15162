#include "common/shutter/best_phase_shutter.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

std::string Px(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

}  // namespace

std::optional<ShutterMode> ParseShutterMode(std::string_view text) {
  if (text == "interval") return ShutterMode::kInterval;
  if (text == "best-phase") return ShutterMode::kBestPhase;
  return std::nullopt;
}

bool BestPhaseShutterOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!std::isfinite(window_cap_s) || window_cap_s <= 0) {
    return fail("shutter window cap must be a positive number of seconds, got " +
                std::to_string(window_cap_s));
  }
  if (!std::isfinite(window_s) || window_s < 0) {
    return fail("shutter window must be ≥ 0 s (0 = one swing period), got " +
                std::to_string(window_s));
  }
  if (window_s > window_cap_s) {
    return fail("shutter window " + Px(window_s) + " s is longer than its cap " + Px(window_cap_s) +
                " s: shorten the window or raise the cap");
  }
  if (!std::isfinite(exposure_ms) || exposure_ms <= 0) {
    return fail("photo exposure must be positive, got " + std::to_string(exposure_ms) + " ms");
  }
  if (!std::isfinite(frame_period_s) || frame_period_s <= 0) {
    return fail("frame period must be positive, got " + std::to_string(frame_period_s) + " s");
  }
  if (!std::isfinite(on_target_px) || on_target_px < 0) {
    return fail("on-target tolerance must be ≥ 0 px, got " + std::to_string(on_target_px));
  }
  if (!std::isfinite(offset_weight) || offset_weight < 0) {
    return fail("offset weight must be ≥ 0, got " + std::to_string(offset_weight));
  }
  if (scenarios < 1 || scenarios > 4096) {
    return fail("scenarios must be 1…4096, got " + std::to_string(scenarios));
  }
  return true;
}

BestPhaseShutter::BestPhaseShutter(ViewForecaster& forecaster, BestPhaseShutterOptions options)
    : forecaster_(forecaster) {
  SetOptions(options);
}

void BestPhaseShutter::SetOptions(const BestPhaseShutterOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  options_ = options;
}

void BestPhaseShutter::Request() {
  if (!open_) requested_ = true;
}

double BestPhaseShutter::Cost(double speed_px_per_frame, double offset_px) const {
  const double exposure_frames = options_.exposure_s() / options_.frame_period_s;
  return speed_px_per_frame * exposure_frames +
         options_.offset_weight * std::max(0.0, offset_px - options_.on_target_px);
}

double BestPhaseShutter::ExpectedCostOfWaiting(const ShutterFrame& frame, int frames) const {
  frames = std::max(frames, 1);
  const cv::Point2d sigma = forecaster_.error_rms();
  std::vector<cv::Point2d> path(static_cast<std::size_t>(frames) + 1);
  path[0] = frame.offset_px;
  for (int k = 1; k <= frames; ++k) path[static_cast<std::size_t>(k)] = forecaster_.Forecast(k);
  const auto scenarios = static_cast<std::size_t>(options_.scenarios);
  // cost[k − 1][s]: frame k's cost in scenario s.
  std::vector<std::vector<double>> cost(static_cast<std::size_t>(frames),
                                        std::vector<double>(scenarios));
  std::mt19937 random(options_.seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (std::size_t s = 0; s < scenarios; ++s) {
    cv::Point2d before = path[0];
    for (std::size_t k = 1; k < path.size(); ++k) {
      const cv::Point2d at =
          path[k] + cv::Point2d(sigma.x * normal(random), sigma.y * normal(random));
      const cv::Point2d step = at - before;
      cost[k - 1][s] = Cost(std::hypot(step.x, step.y), std::hypot(at.x, at.y));
      before = at;
    }
  }
  // The last frame is taken whatever it costs; an earlier one only when it beats going on.
  double value = 0;
  for (std::size_t s = 0; s < scenarios; ++s) value += cost.back()[s];
  value /= static_cast<double>(scenarios);
  for (std::size_t k = cost.size() - 1; k-- > 0;) {
    double sum = 0;
    for (std::size_t s = 0; s < scenarios; ++s) sum += std::min(cost[k][s], value);
    value = sum / static_cast<double>(scenarios);
  }
  return value;
}

ShutterShot BestPhaseShutter::Fire(const ShutterFrame& frame, std::string reason) {
  ShutterShot shot;
  shot.wait_s = static_cast<double>(frame.time_us - opened_us_) / 1e6;
  shot.reason = std::move(reason);
  shot.offset_px = std::hypot(frame.offset_px.x, frame.offset_px.y);
  if (frame.trusted && previous_ && previous_->trusted) {
    const cv::Point2d step = frame.offset_px - previous_->offset_px;
    shot.speed_px_per_frame = std::hypot(step.x, step.y);
  }
  shot.blur_px = shot.speed_px_per_frame * options_.exposure_s() / options_.frame_period_s;
  shot.lock_lost = !frame.trusted;
  shot.mode = options_.mode;
  shot.exposure_ms = options_.exposure_ms;
  open_ = false;
  return shot;
}

std::optional<ShutterShot> BestPhaseShutter::OnFrame(const ShutterFrame& frame) {
  forecaster_.Observe(frame);
  std::optional<ShutterShot> shot = Decide(frame);
  previous_ = frame;
  return shot;
}

std::optional<ShutterShot> BestPhaseShutter::Decide(const ShutterFrame& frame) {
  if (requested_ && !open_) {
    requested_ = false;
    open_ = true;
    opened_us_ = frame.time_us;
    trusted_in_window_ = false;
    if (options_.mode == ShutterMode::kInterval) return Fire(frame, "interval shutter: at once");
    if (!forecaster_.trained()) return Fire(frame, "no trained predictor yet: fired at once");
    double window_s = options_.window_s;
    if (window_s == 0) {
      const std::optional<double> period = forecaster_.period_frames();
      if (!period) return Fire(frame, "no swing period seen yet: fired at once");
      window_s = *period * options_.frame_period_s;
    }
    window_s = std::min(window_s, options_.window_cap_s);
    deadline_us_ = opened_us_ + static_cast<std::int64_t>(std::llround(window_s * 1e6));
  }
  if (!open_) return std::nullopt;

  if (frame.trusted) trusted_in_window_ = true;
  // Frames after this one still inside the window.
  const double period_us = options_.frame_period_s * 1e6;
  const int left = static_cast<int>(
      std::floor(static_cast<double>(deadline_us_ - frame.time_us) / period_us + 1e-6));
  if (left <= 0) {
    if (!trusted_in_window_) return Fire(frame, "lock not trusted in the window: fired at its end");
    if (!frame.trusted) return Fire(frame, "lock not trusted at the window's end: fired anyway");
    return Fire(frame, "window end");
  }
  if (!frame.trusted) return std::nullopt;
  // Its speed needs the frame before measured too.
  if (!previous_ || !previous_->trusted) return std::nullopt;
  if (!forecaster_.trained()) return Fire(frame, "predictor lost its model: fired at once");
  const cv::Point2d step = frame.offset_px - previous_->offset_px;
  const double now =
      Cost(std::hypot(step.x, step.y), std::hypot(frame.offset_px.x, frame.offset_px.y));
  const double waiting = ExpectedCostOfWaiting(frame, left);
  // A tie goes to the frame in hand: waiting for an equal frame only adds wait.
  if (now <= waiting * (1 + 1e-9) + 1e-12) {
    return Fire(frame, "quietest predicted moment: cost " + Px(now) + " px now, " + Px(waiting) +
                           " px expected by waiting");
  }
  return std::nullopt;
}

}  // namespace kapfix
