#include "agent/config/agent_config.hpp"

#include <algorithm>
#include <cctype>
#include <set>

#include "agent/config/config_reader.hpp"
#include "agent/config/options_from_settings.hpp"
#include "common/shutter/best_phase_shutter.hpp"
#include "kapfix/v1/command.pb.h"

namespace kapfix::agent {
namespace {

// Wraps a ParseX(std::string_view) → optional<T> for ConfigReader::ReadParsed.
template <typename T, typename Parse>
auto Enum(Parse parse, const char* choices) {
  return [parse, choices](const std::string& text, T* value, std::string* reason) {
    const auto parsed = parse(text);
    if (!parsed) {
      *reason = "unknown value '" + text + "' (" + choices + ")";
      return false;
    }
    *value = *parsed;
    return true;
  };
}

void ReadSimulation(ConfigReader& r, SimulationConfig* c) {
  r.Read("scene", &c->scene);
  r.ReadParsed<MotionKind>("motion", &c->motion, Enum<MotionKind>(ParseMotionKind, "kite or boat"));
  r.Read("seed", &c->seed);
  r.Read("gusts", &c->gusts);
}

void ReadCamera(ConfigReader& r, CameraConfig* c) {
  r.ReadParsed<CameraBackend>("backend", &c->backend,
                              Enum<CameraBackend>(ParseCameraBackend, "sim, v4l2 or aravis"));
  r.Read("device", &c->device);
  r.Read("width", &c->width);
  r.Read("height", &c->height);
  r.Read("fps", &c->fps);
  r.Read("format", &c->format);
}

void ReadServoAxis(ConfigReader& r, ServoAxisConfig* c) {
  r.Read("channel", &c->mapping.channel);
  r.Read("center_us", &c->mapping.center_us);
  r.Read("us_per_deg", &c->mapping.us_per_deg);
  r.Read("min_us", &c->mapping.min_us);
  r.Read("max_us", &c->mapping.max_us);
  r.Read("min_deg", &c->limits.min_deg);
  r.Read("max_deg", &c->limits.max_deg);
  r.Read("max_rate_deg_per_s", &c->limits.max_rate_deg_per_s);
  r.Read("park_deg", &c->limits.park_deg);
  r.Read("play_deg", &c->play_deg);
}

void ReadServo(ConfigReader& r, ServoConfig* c) {
  r.ReadParsed<ServoBackend>("backend", &c->backend,
                             Enum<ServoBackend>(ParseServoBackend, "sim, maestro or pca9685"));
  r.Read("device", &c->device);
  r.Read("baud", &c->baud);
  r.Read("maestro_timeout_ms", &c->maestro_timeout_ms);
  r.ReadInteger("i2c_address", &c->i2c_address);
  r.Read("pwm_hz", &c->pwm_hz);
  r.Read("oscillator_hz", &c->oscillator_hz);
  r.ReadObject("pan", [c](ConfigReader& axis) {
    ReadServoAxis(axis, &c->pan);
    return axis.ok();
  });
  r.ReadObject("tilt", [c](ConfigReader& axis) {
    ReadServoAxis(axis, &c->tilt);
    return axis.ok();
  });
}

// The SSP swing's length; what is searched and how are operator settings ("settings").
void ReadSearch(ConfigReader& r, SearchConfig* c) {
  r.Read("swing_frames", &c->swing_frames);
  r.Read("swing_seconds", &c->swing_seconds);
}

void ReadLink(ConfigReader& r, LinkConfig* c) {
  r.Read("command", &c->command_address);
  r.Read("stream", &c->stream_address);
  r.Read("heartbeat_ms", &c->heartbeat_ms);
  r.Read("curve_secret_key_file", &c->curve_secret_key_file);
  r.Read("curve_authorized_keys_file", &c->curve_authorized_keys_file);
  r.Read("command_rate_per_s", &c->command_rate_per_s);
  r.Read("command_burst", &c->command_burst);
  r.Read("all_commands_rate_per_s", &c->all_commands_rate_per_s);
}

void ReadAgent(ConfigReader& r, AgentConfig* c) {
  r.Read("agent_id", &c->agent_id);
  r.ReadObject("simulation", [c](ConfigReader& s) {
    ReadSimulation(s, &c->simulation);
    return s.ok();
  });
  r.ReadObject("camera", [c](ConfigReader& s) {
    ReadCamera(s, &c->camera);
    return s.ok();
  });
  r.ReadObject("servo", [c](ConfigReader& s) {
    ReadServo(s, &c->servo);
    return s.ok();
  });
  r.ReadObject("search", [c](ConfigReader& s) {
    ReadSearch(s, &c->search);
    return s.ok();
  });
  r.ReadObject("link", [c](ConfigReader& s) {
    ReadLink(s, &c->link);
    return s.ok();
  });
  r.ReadObject("photos", [c](ConfigReader& s) {
    s.Read("dir", &c->photos.dir);
    return s.ok();
  });
  r.Read("watchdog_ms", &c->watchdog_ms);
  r.Read("state_dir", &c->state_dir);
  r.Read("resume", &c->resume);
  // The operator settings and the lens profiles (settings messages): agent/config_file reads them.
  r.Skip("settings");
  r.Skip("lenses");
  r.Finish();
}

// Sections and keys of the file before the operator settings became "settings" (issue 11).
bool IsMovedSetting(const std::string& error) {
  for (const char* moved : {"controller:", "video:", "lens:", "camera.", "search.", "photos."}) {
    if (error.rfind(moved, 0) == 0 && error.find("unknown key") != std::string::npos) return true;
  }
  return false;
}

bool IsAgentId(const std::string& id) {
  return !id.empty() && id.size() <= 64 && std::all_of(id.begin(), id.end(), [](unsigned char ch) {
    return std::isalnum(ch) || ch == '.' || ch == '_' || ch == '-';
  });
}

// "gains": the settings message's name in the configuration file's "settings" object and in
// reasons, the settings command (Command.set_gains) that carries it without its "set_".
std::string SettingsGroupName(const google::protobuf::Message& settings) {
  const google::protobuf::Descriptor& command = *kapfix::v1::Command::descriptor();
  for (int i = 0; i < command.field_count(); ++i) {
    const google::protobuf::FieldDescriptor& field = *command.field(i);
    if (field.message_type() == settings.GetDescriptor() && field.name().rfind("set_", 0) == 0) {
      return field.name().substr(4);
    }
  }
  return settings.GetDescriptor()->name();
}

// "<group>.<field>: not set" for the first setting that is absent: a held
// settings message has every one (its initial value or what was set since).
std::string MissingSetting(const google::protobuf::Message& settings, const std::string& group) {
  const google::protobuf::Descriptor& type = *settings.GetDescriptor();
  for (int i = 0; i < type.field_count(); ++i) {
    const google::protobuf::FieldDescriptor& field = *type.field(i);
    if (kapfix::v1::SettingOf(field) == nullptr || field.is_repeated()) continue;
    // An enum without presence at *_UNSPECIFIED (0) is as unset.
    if (!settings.GetReflection()->HasField(settings, &field)) {
      return group + "." + field.name() + ": not set";
    }
  }
  return "";
}

}  // namespace

bool AgentConfig::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (!IsAgentId(agent_id)) {
    return fail("agent_id: must be 1…64 characters of A-Z a-z 0-9 . _ -, got '" + agent_id + "'");
  }
  if (!simulation.IsValid(error) || !camera.IsValid(error) || !servo.IsValid(error)) return false;
  if (lenses.empty()) return fail("lenses: at least one lens profile is needed");
  if (lenses.size() > kMaxLensProfiles) {
    return fail("lenses: " + std::to_string(lenses.size()) + " lens profiles, at most " +
                std::to_string(kMaxLensProfiles) + " (reuse a name to change a profile)");
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < lenses.size(); ++i) {
    std::string reason;
    if (!lenses[i].IsValid(&reason)) {
      return fail("lenses[" + std::to_string(i) + "]: " + reason);
    }
    if (!names.insert(lenses[i].name).second) {
      return fail("lenses[" + std::to_string(i) + "]: lens name '" + lenses[i].name +
                  "' is used twice");
    }
  }
  if (names.count(lens) == 0) return fail("lens: no lens profile named '" + lens + "'");
  if (!search.IsValid(error) || !link.IsValid(error) || !photos.IsValid(error)) return false;
  // Every settings message in the schema's ranges (an absent field would read 0: not allowed).
  for (const google::protobuf::Message* settings :
       std::initializer_list<const google::protobuf::Message*>{&gains, &photo, &video}) {
    const std::string group = SettingsGroupName(*settings);
    std::string reason = kapfix::v1::CheckSettings(*settings, group);
    if (reason.empty()) reason = MissingSetting(*settings, group);
    if (!reason.empty()) return fail(reason);
  }
  // Across fields (the window within its cap): the shutter's own check.
  if (std::string reason; !OptionsFromSettings<BestPhaseShutterOptions>(photo).IsValid(&reason)) {
    return fail("photo: " + reason);
  }
  if (search.patch_px > std::min(camera.width, camera.height)) {
    return fail("search.patch_px: " + std::to_string(search.patch_px) +
                " px does not fit in the camera's " + std::to_string(camera.width) + "x" +
                std::to_string(camera.height) + " frame");
  }
  if (state_dir.empty()) return fail("state_dir: must name a folder");
  if (watchdog_ms < 20 || watchdog_ms > 60000) {
    return fail("watchdog_ms: must be 20…60000 ms, got " + std::to_string(watchdog_ms));
  }
  if (servo.backend == ServoBackend::kMaestro) {
    // The Maestro parks the servos when no command came for maestro_timeout_ms: the loop
    // commands once per frame, so a shorter timeout parks in flight; the watchdog parks
    // (a command) after watchdog_ms, so a longer one adds nothing and parks later if the
    // agent dies.
    const double frame_ms = 1000.0 / camera.fps;
    if (servo.maestro_timeout_ms > watchdog_ms) {
      return fail("servo.maestro_timeout_ms: " + std::to_string(servo.maestro_timeout_ms) +
                  " ms must not exceed watchdog_ms (" + std::to_string(watchdog_ms) + " ms)");
    }
    if (!(servo.maestro_timeout_ms > frame_ms)) {
      return fail("servo.maestro_timeout_ms: " + std::to_string(servo.maestro_timeout_ms) +
                  " ms must exceed a camera frame period (" + std::to_string(frame_ms) +
                  " ms at camera.fps " + std::to_string(camera.fps) + ")");
    }
  }
  return true;
}

void AgentConfig::ApplyLensCalibration(const std::string& lens_name,
                                       const LensCalibration& calibration) {
  for (LensProfile& profile : lenses) {
    if (profile.name == lens_name) profile.ApplyCalibration(calibration);
  }
}

const LensProfile& AgentConfig::active_lens() const {
  for (const LensProfile& profile : lenses) {
    if (profile.name == lens) return profile;
  }
  return lenses.front();
}

bool ReadAgentDevices(const nlohmann::json& json, AgentConfig* config, std::string* error) {
  ConfigReader reader(json, "");
  if (reader.ok()) ReadAgent(reader, config);
  if (reader.ok()) return true;
  if (error) {
    *error = reader.error();
    if (IsMovedSetting(*error)) {
      *error +=
          "; the operator settings moved to \"settings\": the kapfix.v1 settings messages in "
          "protobuf's JSON mapping, e.g. {\"settings\": {\"gains\": {\"p\": 0.8}}} "
          "(resources/README.md)";
    }
  }
  return false;
}

}  // namespace kapfix::agent
