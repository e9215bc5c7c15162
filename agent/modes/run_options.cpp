#include "agent/modes/run_options.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "agent/config/options_from_settings.hpp"
#include "common/shutter/best_phase_shutter.hpp"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {
namespace {

constexpr std::array<int, 3> kPatchSizeCandidates{50, 100, 150};  // [px] the thesis's

}  // namespace

ControllerGains MakeGains(const kapfix::v1::Gains& gains) {
  return OptionsFromSettings<ControllerGains>(gains);
}

SearchOptions MakeSearchOptions(const SearchConfig& search) {
  SearchOptions o;
  o.axis = search.axis;
  o.range = search.range_px;
  o.cross_range = std::min(o.cross_range, search.range_px);
  o.subpixel = search.subpixel;
  return o;
}

FixationOptions MakeFixationOptions(const SearchConfig& search, int slice,
                                    FixationOptions::Reference reference) {
  FixationOptions o;
  o.search = MakeSearchOptions(search);
  o.sampling = search.sampling;
  o.channel = search.channel;
  o.patch_size = search.patch_px;
  o.slice_count = search.slices;
  o.slice = slice;
  o.reference = reference;
  return o;
}

SliceSelectionOptions MakeSliceSelectionOptions(const SearchConfig& search) {
  SliceSelectionOptions o;
  o.slice_count = search.slices;
  o.patch_size = search.patch_px;
  o.sampling = search.sampling;
  o.search = MakeSearchOptions(search);
  o.hysteresis_px = search.hysteresis_px;
  o.score = search.score;
  return o;
}

PatchSizeSelectionOptions MakePatchSizeSelectionOptions(const SearchConfig& search,
                                                        cv::Size plane) {
  PatchSizeSelectionOptions o;
  o.sizes.clear();
  for (const int size : kPatchSizeCandidates) {
    if (size <= std::min(plane.width, plane.height)) o.sizes.push_back(size);
  }
  o.sampling = search.sampling;
  o.search = MakeSearchOptions(search);
  return o;
}

SimulatedPlatformOptions::Motion ToPlatformMotion(MotionKind kind) {
  return kind == MotionKind::kBoat ? SimulatedPlatformOptions::Motion::kBoat
                                   : SimulatedPlatformOptions::Motion::kKite;
}

SimulatedPlatformOptions MakePlatformOptions(const AgentConfig& config) {
  const ClosedLoopOptions base =
      ClosedLoopOptions::ForMotion(ToPlatformMotion(config.simulation.motion));
  SimulatedPlatformOptions o = base.platform;
  o.kite.seed = config.simulation.seed;
  o.kite.gusts = config.simulation.gusts;
  o.boat.seed = config.simulation.seed;
  o.camera.seed = config.simulation.seed;
  o.camera.frame_size = {config.camera.width, config.camera.height};
  // The lens profile is what the controller believes; the simulated truth differs from it
  // by the world's calibration error.
  o.px_per_deg = config.simulation.world.calibration_error / config.active_lens().DegPerPxPan();
  const bool default_gusts = config.simulation.world.gusts == WorldOptions::Gusts::kPeriodic;
  config.simulation.world.ApplyTo(&o);
  // --blur smears each frame over the photo's exposure (issue 13), at most one frame period.
  if (config.simulation.world.blur) {
    o.camera.motion_blur_exposure =
        std::min(1.0, OptionsFromSettings<BestPhaseShutterOptions>(config.photo).exposure_s() *
                          config.camera.fps);
  }
  if (default_gusts) o.kite.gusts = config.simulation.gusts;
  o.pan.min_deg = config.servo.pan.limits.min_deg;
  o.pan.max_deg = config.servo.pan.limits.max_deg;
  o.pan.initial_deg = config.servo.pan.limits.park_deg;
  o.tilt.min_deg = config.servo.tilt.limits.min_deg;
  o.tilt.max_deg = config.servo.tilt.limits.max_deg;
  o.tilt.initial_deg = config.servo.tilt.limits.park_deg;
  // The simulated servos are exactly as fast as the limiter lets the agent command them (the
  // configured max_rate is the servo's rated speed or less): every command it sends is one
  // the servo reaches, so the loop's belief of the angle (the command) can be right.
  o.pan.rate_limit_deg_per_frame = config.servo.pan.limits.max_rate_deg_per_s / config.camera.fps;
  o.tilt.rate_limit_deg_per_frame = config.servo.tilt.limits.max_rate_deg_per_s / config.camera.fps;
  return o;
}

std::optional<std::string> SimulatedWorldScaleNote(const AgentConfig& config) {
  const AgentConfig built_in;
  // [1] how much faster (in seconds) and wider (in degrees) this camera sees the world's swing
  const double faster = config.camera.fps / built_in.camera.fps;
  const double wider = config.active_lens().DegPerPxPan() / built_in.active_lens().DegPerPxPan();
  constexpr double kSame = 0.02;  // [1] closer than this is the same camera
  if (std::abs(faster - 1) < kSame && std::abs(wider - 1) < kSame) return std::nullopt;
  char line[320];
  std::snprintf(line, sizeof line,
                "the simulated swing is defined in frames and pixels for %g frames/s and %g "
                "deg/px; at this configuration's %g frames/s and %.3g deg/px it is %.2g× as fast "
                "and %.2g× as wide in angle, so its figures do not compare with the built-in "
                "configuration's",
                built_in.camera.fps, built_in.active_lens().DegPerPxPan(), config.camera.fps,
                config.active_lens().DegPerPxPan(), faster, wider);
  return std::string(line);
}

SliceReportContext MakeSliceReportContext(const SearchConfig& search) {
  SliceReportContext report;
  report.score = search.score;
  report.hysteresis_px = search.hysteresis_px;
  report.patch_size_px = search.patch_px;
  report.strategy = search.strategy;
  return report;
}

LostLockSspOptions MakeLostLockSspOptions(const AgentConfig& config) {
  LostLockSspOptions o;
  const double wait_s = config.search.ssp_after_lost_s;
  o.after_frames =
      wait_s > 0 ? std::max(1, static_cast<int>(std::lround(wait_s * config.camera.fps))) : 0;
  // The free swing ends at whichever of its two deadlines comes first (simulated time).
  o.run_frames = std::max(
      2, std::min(config.search.swing_frames,
                  static_cast<int>(std::lround(config.search.swing_seconds * config.camera.fps))));
  o.selection = MakeSliceSelectionOptions(config.search);
  return o;
}

ClosedLoopOptions MakeClosedLoopOptions(const AgentConfig& config) {
  ClosedLoopOptions o = ClosedLoopOptions::ForMotion(ToPlatformMotion(config.simulation.motion));
  AgentConfig without_world = config;
  without_world.simulation.world = WorldOptions{};
  o.platform = MakePlatformOptions(without_world);
  o.world = config.simulation.world;
  o.fixation = MakeFixationOptions(config.search, o.fixation.slice, o.fixation.reference);
  o.strategy = config.search.strategy;
  o.controller = kapfix::v1::WordOf(config.gains.controller());
  o.gains = MakeGains(config.gains);
  o.frame_period_s = 1.0 / config.camera.fps;
  // The free swing ends at whichever of its two deadlines comes first (simulated time).
  o.ssp_frames =
      std::min(config.search.swing_frames,
               static_cast<int>(std::lround(config.search.swing_seconds * config.camera.fps)));
  o.ssp_after_lost_frames = MakeLostLockSspOptions(config).after_frames;
  return o;
}

bool SameLoop(const AgentConfig& a, const AgentConfig& b) {
  const SearchConfig& s = a.search;
  const SearchConfig& t = b.search;
  const LensProfile& l = a.active_lens();
  const LensProfile& m = b.active_lens();
  return s.strategy == t.strategy && ToString(s.sampling) == ToString(t.sampling) &&
         s.sampling.seed == t.sampling.seed && s.patch_px == t.patch_px && s.slices == t.slices &&
         s.axis == t.axis && s.range_px == t.range_px && s.channel == t.channel &&
         s.subpixel == t.subpixel && s.score == t.score && s.hysteresis_px == t.hysteresis_px &&
         a.gains.controller() == b.gains.controller() && l.name == m.name &&
         l.DegPerPxPan() == m.DegPerPxPan() && l.DegPerPxTilt() == m.DegPerPxTilt();
}

}  // namespace kapfix::agent
