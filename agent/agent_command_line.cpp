#include "agent/agent_command_line.hpp"

#include <cmath>

#include "agent/config/device_spec.hpp"
#include "agent/config_file/agent_config_file.hpp"

namespace kapfix::agent {

AgentCommandLine::AgentCommandLine(CLI::App& app) : setting_flags_(app) {
  AddRunFlags(app);
  AddLinkAndFolderFlags(app);
  AddDeviceFlags(app);
  AddWorldFlags(app);
  AddPhotoFlags(app);
}

void AgentCommandLine::AddRunFlags(CLI::App& app) {
  app.add_option("--config", config_path_,
                 "configuration file (resources/README.md); default: built-in defaults, which "
                 "fly in simulation");
  app.add_flag("--sim", force_sim_, "simulated camera and servos, whatever the config says");
  app.add_option("--scene", scene_,
                 std::string("simulation: scene photo (default ") + kDefaultScene + ")");
  app.add_option("--motion", motion_, "simulation: platform motion")
      ->check(CLI::IsMember({"kite", "boat"}));
  auto* duration_opt =
      app.add_option("--duration", duration_s_, "seconds of flight at the camera's fps, then stop")
          ->check(CLI::PositiveNumber);
  app.add_option("--frames", frames_, "frames to process, then stop")
      ->check(CLI::PositiveNumber)
      ->excludes(duration_opt);
  app.add_option("--report", report_dir_,
                 "write DIR/summary.json, DIR/telemetry.csv, DIR/displacement.png at the end");
  app.add_option("--seed", seed_, "simulation seed (overrides the config)");
  app.add_option("--mode", start_mode_, "mode on the first frame")
      ->check(CLI::IsMember({"idle", "fixate", "follow", "ssp", "pss", "calibrate"}));
  app.add_flag("--no-resume", no_resume_,
               "start from the configuration, not from the settings, mode and fixated view the "
               "previous run stored in the state folder (also config key resume: false)");
  app.add_flag("--max-speed", max_speed_,
               "simulation: frames as fast as the machine allows, not at the camera's rate");
}

void AgentCommandLine::AddLinkAndFolderFlags(CLI::App& app) {
  app.add_option("--command-address", command_address_,
                 "ZeroMQ address for commands (overrides link.command, e.g. tcp://127.0.0.1:5555)");
  app.add_option("--stream-address", stream_address_,
                 "ZeroMQ address for the streams (overrides link.stream)");
  app.add_flag("--insecure", insecure_,
               "let the link listen beyond this machine without CurveZMQ keys (not for a field)");
  app.add_option("--photos", photos_dir_,
                 "folder for photos and recordings (overrides photos.dir)");
  app.add_option(
      "--state-dir", state_dir_,
      "folder for the agent's calibrations per lens and what a restart resumes (overrides "
      "state_dir)");
}

void AgentCommandLine::AddDeviceFlags(CLI::App& app) {
  app.add_option("--camera", camera_spec_,
                 "camera, overriding the config: sim, v4l2:/dev/video0, aravis[:ID-or-address]");
  app.add_option("--servos", servos_spec_,
                 "servo controller, overriding the config: sim, maestro:/dev/kapfix-maestro, "
                 "pca9685:/dev/i2c-1[@0x40]");
  app.add_flag("--preflight", preflight_,
               "check config, keys, devices, photo folder and clock; print PASS/FAIL lines; exit "
               "1 if any fails");
}

void AgentCommandLine::AddWorldFlags(CLI::App& app) {
  app.add_option("--world", world_preset_, "simulation: nominal|realistic disturbance preset");
  app.add_option("--gusts", world_gusts_, "simulation: periodic|broadband|off");
  app.add_option("--period-drift", period_drift_, "simulation: swing period wanders ±F (0…0.5)");
  app.add_flag("--sway", sway_, "simulation: a slower second sway of the line");
  app.add_option("--roll-deg", roll_deg_, "simulation: image roll up to ±D degrees (0…30)");
  app.add_flag("--blur", blur_, "simulation: motion blur with the view's speed");
  app.add_flag("--exposure-steps", exposure_steps_, "simulation: auto-exposure steps ±20 %");
  app.add_option("--latency-jitter", latency_jitter_, "simulation: servo latency 1…N frames");
  app.add_option("--frame-drops", frame_drops_, "simulation: share of frames lost (0…0.5)");
  app.add_option("--calibration-error", calibration_error_,
                 "simulation: lens calibration = F × the true deg/px (0.5…2)");
}

void AgentCommandLine::AddPhotoFlags(CLI::App& app) {
  // Issue 13: which camera takes photos (a USB still camera through libgphoto2, or ours).
  app.add_option("--photo-camera", photo_camera_,
                 "camera for photos: agent (the tracking camera) or gphoto2 (a USB still camera; "
                 "falls back to agent when it cannot)")
      ->check(CLI::IsMember({"agent", "gphoto2"}));
  app.add_flag("--still-camera-delete", still_camera_delete_,
               "delete each still-camera photo on the camera once stored on the agent (default: "
               "the camera's card keeps it too)");
}

bool AgentCommandLine::BuildWorld(WorldOptions* world, std::string* error) const {
  const bool any_world = !world_preset_.empty() || !world_gusts_.empty() || period_drift_ ||
                         roll_deg_ || frame_drops_ || calibration_error_ || latency_jitter_ ||
                         sway_ || blur_ || exposure_steps_;
  if (any_world && !force_sim_) {
    *error = "the simulated world's flags (--world, --gusts, …) need --sim";
    return false;
  }
  if (!world_preset_.empty()) {
    const auto preset = WorldOptions::Preset(world_preset_);
    if (!preset) {
      *error = "--world must be nominal or realistic, got " + world_preset_;
      return false;
    }
    *world = *preset;
  }
  if (!world_gusts_.empty()) {
    const auto gusts = ParseWorldGusts(world_gusts_);
    if (!gusts) {
      *error = "--gusts must be periodic, broadband or off, got " + world_gusts_;
      return false;
    }
    world->gusts = *gusts;
  }
  if (period_drift_) world->period_drift = *period_drift_;
  if (roll_deg_) world->roll_deg = *roll_deg_;
  if (frame_drops_) world->frame_drops = *frame_drops_;
  if (calibration_error_) world->calibration_error = *calibration_error_;
  if (latency_jitter_) world->latency_jitter = *latency_jitter_;
  world->sway = world->sway || sway_;
  world->blur = world->blur || blur_;
  world->exposure_steps = world->exposure_steps || exposure_steps_;
  return world->IsValid(error);
}

bool AgentCommandLine::BuildConfig(AgentConfig* config, std::string* error) const {
  WorldOptions world;
  if (!BuildWorld(&world, error)) return false;
  if (config_path_.empty()) {
    *config = BuiltInConfig(motion_.empty() ? MotionKind::kKite : *ParseMotionKind(motion_));
  } else {
    if (!LoadAgentConfig(config_path_, config, error)) return false;
    if (!motion_.empty()) config->simulation.motion = *ParseMotionKind(motion_);
  }
  config->simulation.world = world;
  ApplyOverrides(config);
  if (!setting_flags_.Apply(config, error)) return false;
  if (!camera_spec_.empty() && !ApplyCameraSpec(camera_spec_, &config->camera, error)) {
    return false;
  }
  return servos_spec_.empty() || ApplyServoSpec(servos_spec_, &config->servo, error);
}

void AgentCommandLine::ApplyOverrides(AgentConfig* config) const {
  if (seed_) config->simulation.seed = *seed_;
  if (!scene_.empty()) config->simulation.scene = scene_;
  if (config->simulation.scene.empty()) config->simulation.scene = kDefaultScene;
  if (!command_address_.empty()) config->link.command_address = command_address_;
  if (!stream_address_.empty()) config->link.stream_address = stream_address_;
  if (!photos_dir_.empty()) config->photos.dir = photos_dir_;
  if (!state_dir_.empty()) config->state_dir = state_dir_;
}

AgentOptions AgentCommandLine::BuildOptions(const AgentConfig& config) const {
  AgentOptions options;
  options.simulate = force_sim_;
  options.real_time = !max_speed_;
  options.start_mode = *ParseAgentMode(start_mode_);
  options.keep_telemetry = !report_dir_.empty();
  options.insecure = insecure_;
  options.still_camera_delete = still_camera_delete_;
  if (!photo_camera_.empty()) {
    options.photo_camera = photo_camera_ == "gphoto2" ? kapfix::v1::PHOTO_CAMERA_GPHOTO2
                                                      : kapfix::v1::PHOTO_CAMERA_AGENT;
  }
  options.resume = !no_resume_;
  if (frames_) options.frames = *frames_;
  if (duration_s_) {
    options.frames = static_cast<std::uint64_t>(std::llround(*duration_s_ * config.camera.fps));
    if (options.frames == 0) options.frames = 1;
  }
  return options;
}

PreflightOptions AgentCommandLine::BuildPreflight() const {
  PreflightOptions checks{.simulate = force_sim_};
  if (photo_camera_ == "gphoto2") checks.photo_camera = kapfix::v1::PHOTO_CAMERA_GPHOTO2;
  return checks;
}

}  // namespace kapfix::agent
