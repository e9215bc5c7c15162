#pragma once

// kapfix-agent's command line (SPEC §4): its flags, and what they make of the configuration,
// the agent's options and the preflight checks. main.cpp only wires: parse, build, run, report.

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>

#include "agent/agent.hpp"
#include "agent/config/agent_config.hpp"
#include "agent/preflight/preflight.hpp"
#include "agent/setting_flags.hpp"

namespace kapfix::agent {

// The scene flown in simulation when neither the config nor --scene names one.
inline constexpr const char* kDefaultScene = "/usr/share/doc/opencv-doc/examples/data/aero1.jpg";

class AgentCommandLine {
 public:
  // Declares every flag on `app`; app's parse writes their values into this object, which
  // must therefore stay where it is (not copyable or movable).
  explicit AgentCommandLine(CLI::App& app);
  AgentCommandLine(const AgentCommandLine&) = delete;
  AgentCommandLine& operator=(const AgentCommandLine&) = delete;

  // The configuration the flags ask for: the config file (or the built-in one) with the flags
  // over it. False with a one-line reason naming the flag or the file.
  bool BuildConfig(AgentConfig* config, std::string* error) const;
  // The agent's options; `config` as BuildConfig made it (its fps turns --duration into frames).
  AgentOptions BuildOptions(const AgentConfig& config) const;
  PreflightOptions BuildPreflight() const;

  bool preflight() const { return preflight_; }
  bool force_sim() const { return force_sim_; }
  const std::string& report_dir() const { return report_dir_; }

 private:
  void AddRunFlags(CLI::App& app);
  void AddLinkAndFolderFlags(CLI::App& app);
  void AddDeviceFlags(CLI::App& app);
  void AddWorldFlags(CLI::App& app);
  void AddPhotoFlags(CLI::App& app);
  // The simulated world's preset and single flags over it; refused without --sim.
  bool BuildWorld(WorldOptions* world, std::string* error) const;
  // The flags that override a config key and are no setting, over `config`.
  void ApplyOverrides(AgentConfig* config) const;

  // The settings' flags (--controller, --shutter-window, …): made from the settings schema.
  SettingFlags setting_flags_;

  std::string config_path_;
  bool force_sim_ = false;
  std::string scene_;
  std::string motion_;
  std::optional<double> duration_s_;
  std::optional<std::uint64_t> frames_;
  std::string report_dir_;
  std::optional<std::uint32_t> seed_;
  std::string command_address_;
  std::string stream_address_;
  std::string photos_dir_;
  std::string state_dir_;
  std::string start_mode_ = "fixate";
  bool insecure_ = false;
  bool no_resume_ = false;
  bool max_speed_ = false;
  // Field deployment (issue 10): one device from the command line, and checks without flying.
  std::string camera_spec_;
  std::string servos_spec_;
  bool preflight_ = false;
  // The simulated world's disturbances (issue 9): a preset, then single flags over it.
  std::string world_preset_;
  std::string world_gusts_;
  std::optional<double> period_drift_, roll_deg_, frame_drops_, calibration_error_;
  std::optional<int> latency_jitter_;
  bool sway_ = false, blur_ = false, exposure_steps_ = false;
  // Photos (issue 13): which camera takes them (when: the settings' flags).
  std::string photo_camera_;
  bool still_camera_delete_ = false;
};

}  // namespace kapfix::agent
