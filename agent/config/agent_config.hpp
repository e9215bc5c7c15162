#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "agent/config/camera_config.hpp"
#include "agent/config/lens_profile.hpp"
#include "agent/config/link_config.hpp"
#include "agent/config/photo_config.hpp"
#include "agent/config/search_config.hpp"
#include "agent/config/servo_config.hpp"
#include "agent/config/simulation_config.hpp"
#include "kapfix/v1/settings.pb.h"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {

// kapfix-agent's one configuration (SPEC §4), read from its JSON file by
// agent/config_file/agent_config_file.hpp. Every key, its default and its unit:
// resources/README.md; examples: resources/kite.json, resources/boat.json. A default-built
// AgentConfig is valid and runs everything in simulation.
struct AgentConfig {
  // [count] lens profiles at most: each set_lens with a new name adds one, and every state
  // message carries them all, so a peer must not be able to grow them without bound.
  static constexpr std::size_t kMaxLensProfiles = 64;

  std::string agent_id = "kapfix";  // names the agent in every message; [A-Za-z0-9._-]{1,64}
  SimulationConfig simulation;
  CameraConfig camera;
  ServoConfig servo;
  // Lens profiles, and the name of the one fitted; calibration is stored per profile.
  std::vector<LensProfile> lenses = {
      {.name = "default", .deg_per_px_pan = 0.1, .deg_per_px_tilt = 0.1}};
  std::string lens = "default";
  SearchConfig search;
  // The operator settings held as their kapfix.v1 message: a command merges into it, the
  // state carries it, the controller's options are copied from it by field name
  // (OptionsFromSettings). Defaults: each field's `initial` in settings.proto.
  kapfix::v1::Gains gains = kapfix::v1::InitialSettings<kapfix::v1::Gains>();
  LinkConfig link;
  PhotoConfig photos;
  kapfix::v1::PhotoSettings photo = kapfix::v1::InitialSettings<kapfix::v1::PhotoSettings>();
  kapfix::v1::VideoSettings video = kapfix::v1::InitialSettings<kapfix::v1::VideoSettings>();
  // The agent's own files besides photos: calibrations per lens profile (calibration/).
  std::string state_dir = "/var/lib/kapfix";
  // On start, come back with the settings, mode, slice and fixated view stored in
  // state_dir/resume/ by the previous run (issue 14); false = start from this configuration.
  bool resume = true;
  // [ms] the servos are parked when the control loop has not run for this long.
  int watchdog_ms = 500;

  // Every section, unique lens names, `lens` among them, watchdog 20…60000 ms. The reason
  // starts with the field's path ("servo.pan: …").
  bool IsValid(std::string* error) const;

  const LensProfile& active_lens() const;  // the profile named by `lens` (IsValid first)

  // A calibration of the profile named `lens` (LensProfile::ApplyCalibration); no profile of
  // that name: nothing. One function so that the settings' owner and the control thread,
  // which both hold the calibrated profile, hold the same one.
  void ApplyLensCalibration(const std::string& lens, const LensCalibration& calibration);
};

// Reads the file's parts that are not operator settings (devices, link, folders; everything
// but its "settings" object and its "lenses", which agent/config_file reads) from the
// file's root object into `config`: keys not given keep their values; unknown keys and wrong
// types are errors naming the field ("camera.fps: …"). Does not check IsValid.
bool ReadAgentDevices(const nlohmann::json& json, AgentConfig* config, std::string* error);

}  // namespace kapfix::agent
