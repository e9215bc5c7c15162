#include "common/sim/world_options.hpp"

#include <cmath>
#include <cstdio>

namespace kapfix {
namespace {

constexpr double kSwayAmplitudePx = 20;   // [px] --sway's slow second sway along x
constexpr double kBlurExposure = 0.5;     // [frame periods] --blur's shutter time
constexpr double kExposureStepMax = 0.2;  // [1] --exposure-steps: gain 1 ± up to 20 %
constexpr int kMaxLatencyJitter = 10;     // [frames]

std::string Format(const char* format, double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, format, value);
  return buffer;
}

}  // namespace

std::optional<WorldOptions::Gusts> ParseWorldGusts(std::string_view text) {
  if (text == "off") return WorldOptions::Gusts::kOff;
  if (text == "periodic") return WorldOptions::Gusts::kPeriodic;
  if (text == "broadband") return WorldOptions::Gusts::kBroadband;
  return std::nullopt;
}

std::string_view ToString(WorldOptions::Gusts gusts) {
  switch (gusts) {
    case WorldOptions::Gusts::kOff:
      return "off";
    case WorldOptions::Gusts::kPeriodic:
      return "periodic";
    case WorldOptions::Gusts::kBroadband:
      return "broadband";
  }
  return "?";
}

bool WorldOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!(period_drift >= 0 && period_drift <= 0.5)) {
    return fail("--period-drift must be in 0…0.5, got " + Format("%g", period_drift));
  }
  if (!(roll_deg >= 0 && roll_deg <= 30)) {
    return fail("--roll-deg must be in 0…30 degrees, got " + Format("%g", roll_deg));
  }
  if (latency_jitter != 0 && (latency_jitter < 1 || latency_jitter > kMaxLatencyJitter)) {
    return fail("--latency-jitter must be in 1…" + std::to_string(kMaxLatencyJitter) +
                " frames, got " + std::to_string(latency_jitter));
  }
  if (!(frame_drops >= 0 && frame_drops <= 0.5)) {
    return fail("--frame-drops must be a share in 0…0.5, got " + Format("%g", frame_drops));
  }
  if (!(calibration_error >= 0.5 && calibration_error <= 2.0)) {
    return fail("--calibration-error must be in 0.5…2 (× the true deg/px), got " +
                Format("%g", calibration_error));
  }
  return true;
}

std::string WorldOptions::Describe() const {
  std::string out;
  const auto add = [&out](const std::string& part) { out += (out.empty() ? "" : ", ") + part; };
  if (gusts != Gusts::kPeriodic) add("gusts " + std::string(ToString(gusts)));
  if (period_drift > 0) add("period drift ±" + Format("%g", period_drift));
  if (sway) add("sway");
  if (roll_deg > 0) add("roll ±" + Format("%g", roll_deg) + "°");
  if (blur) add("motion blur");
  if (exposure_steps) add("exposure steps");
  if (latency_jitter > 0) add("servo latency 1…" + std::to_string(latency_jitter) + " frames");
  if (frame_drops > 0) add("frame drops " + Format("%g", 100 * frame_drops) + " %");
  if (calibration_error != 1.0) add("calibration ×" + Format("%g", calibration_error));
  return out.empty() ? "nominal" : out;
}

void WorldOptions::ApplyTo(SimulatedPlatformOptions* platform) const {
  KiteMotionOptions& kite = platform->kite;
  kite.gusts = gusts != Gusts::kOff;
  kite.gust_model = gusts == Gusts::kBroadband ? KiteMotionOptions::GustModel::kBroadband
                                               : KiteMotionOptions::GustModel::kPeriodic;
  kite.period_drift = period_drift;
  kite.sway_amplitude_px = sway ? kSwayAmplitudePx : 0.0;
  platform->camera.roll_max_deg = roll_deg;
  platform->camera.motion_blur_exposure = blur ? kBlurExposure : 0.0;
  platform->camera.exposure_step_max = exposure_steps ? kExposureStepMax : 0.0;
  for (SimulatedServoOptions* servo : {&platform->pan, &platform->tilt}) {
    if (latency_jitter > 0) {
      servo->latency_frames = 1;
      servo->latency_max_frames = latency_jitter;
    }
  }
  platform->pan.seed = platform->camera.seed;
  platform->tilt.seed = platform->camera.seed ^ 0x7469u;  // another stream for tilt
  platform->frame_drop_rate = frame_drops;
}

WorldOptions WorldOptions::Realistic() {
  WorldOptions w;
  w.gusts = Gusts::kBroadband;
  w.period_drift = 0.15;
  w.sway = true;
  w.roll_deg = 3;
  w.blur = true;
  w.exposure_steps = true;
  w.latency_jitter = 2;
  w.frame_drops = 0.02;
  w.calibration_error = 1.3;
  return w;
}

std::optional<WorldOptions> WorldOptions::Preset(std::string_view name) {
  if (name == "nominal") return Nominal();
  if (name == "realistic") return Realistic();
  return std::nullopt;
}

}  // namespace kapfix
