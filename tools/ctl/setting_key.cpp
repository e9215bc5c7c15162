#include "tools/ctl/setting_key.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdint>
#include <limits>
#include <utility>

namespace kapfix::ctl {
namespace {

using kapfix::v1::Command;

std::optional<float> ParseFloat(std::string_view text) {
  float value = 0;
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || text.empty()) return std::nullopt;
  return value;
}

std::optional<std::uint32_t> ParseUint(std::string_view text) {
  std::uint32_t value = 0;
  const auto* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, value);
  if (ec != std::errc() || ptr != end || text.empty()) return std::nullopt;
  return value;
}

std::optional<bool> ParseBool(std::string_view text) {
  if (text == "on" || text == "true" || text == "yes" || text == "1") return true;
  if (text == "off" || text == "false" || text == "no" || text == "0") return false;
  return std::nullopt;
}

// A keyword among `names` (index i ↦ enum value values[i]).
template <typename Enum, std::size_t N>
std::optional<Enum> ParseKeyword(std::string_view text,
                                 const std::array<std::pair<std::string_view, Enum>, N>& names) {
  for (const auto& [name, value] : names) {
    if (text == name) return value;
  }
  return std::nullopt;
}

// Setters of one float / uint / bool field: `Setter` is a member function pointer of the
// settings message reached through `Mutable`.
template <auto Mutable, auto Setter>
bool SetFloat(Command& command, std::string_view text) {
  const auto value = ParseFloat(text);
  if (!value) return false;
  ((command.*Mutable)()->*Setter)(*value);
  return true;
}

template <auto Mutable, auto Setter>
bool SetUint(Command& command, std::string_view text) {
  const auto value = ParseUint(text);
  if (!value) return false;
  ((command.*Mutable)()->*Setter)(*value);
  return true;
}

template <auto Mutable, auto Setter>
bool SetBool(Command& command, std::string_view text) {
  const auto value = ParseBool(text);
  if (!value) return false;
  ((command.*Mutable)()->*Setter)(*value);
  return true;
}

using kapfix::v1::CameraSettings;
using kapfix::v1::Gains;
using kapfix::v1::LensProfile;
using kapfix::v1::SearchSettings;
using kapfix::v1::VideoSettings;

bool SetController(Command& command, std::string_view text) {
  static constexpr std::array<std::pair<std::string_view, kapfix::v1::ControllerKind>, 3> kNames{{
      {"p", kapfix::v1::CONTROLLER_KIND_P},
      {"pid", kapfix::v1::CONTROLLER_KIND_PID},
      {"predictive", kapfix::v1::CONTROLLER_KIND_PREDICTIVE},
  }};
  const auto value = ParseKeyword(text, kNames);
  if (!value) return false;
  command.mutable_set_gains()->set_controller(*value);
  return true;
}

bool SetStrategy(Command& command, std::string_view text) {
  if (text.empty()) return false;
  command.mutable_set_search()->set_strategy(std::string(text));
  return true;
}

bool SetSampling(Command& command, std::string_view text) {
  static constexpr std::array<std::pair<std::string_view, kapfix::v1::Sampling>, 3> kNames{{
      {"all", kapfix::v1::SAMPLING_ALL},
      {"static", kapfix::v1::SAMPLING_STATIC},
      {"random", kapfix::v1::SAMPLING_RANDOM},
  }};
  const auto value = ParseKeyword(text, kNames);
  if (!value) return false;
  command.mutable_set_search()->set_sampling(*value);
  return true;
}

bool SetAxis(Command& command, std::string_view text) {
  static constexpr std::array<std::pair<std::string_view, kapfix::v1::Axis>, 3> kNames{{
      {"x", kapfix::v1::AXIS_X},
      {"y", kapfix::v1::AXIS_Y},
      {"both", kapfix::v1::AXIS_BOTH},
  }};
  const auto value = ParseKeyword(text, kNames);
  if (!value) return false;
  command.mutable_set_search()->set_axis(*value);
  return true;
}

bool SetChannel(Command& command, std::string_view text) {
  static constexpr std::array<std::pair<std::string_view, kapfix::v1::Channel>, 2> kNames{{
      {"green", kapfix::v1::CHANNEL_GREEN},
      {"rgb", kapfix::v1::CHANNEL_RGB_SUM},
  }};
  const auto value = ParseKeyword(text, kNames);
  if (!value) return false;
  command.mutable_set_search()->set_channel(*value);
  return true;
}

bool SetSliceScore(Command& command, std::string_view text) {
  static constexpr std::array<std::pair<std::string_view, kapfix::v1::SliceScoreKind>, 4> kNames{{
      {"dc", kapfix::v1::SLICE_SCORE_KIND_DC},
      {"dc_hysteresis", kapfix::v1::SLICE_SCORE_KIND_DC_HYSTERESIS},
      {"single_shot", kapfix::v1::SLICE_SCORE_KIND_SINGLE_SHOT},
      {"fft", kapfix::v1::SLICE_SCORE_KIND_FFT},
  }};
  const auto value = ParseKeyword(text, kNames);
  if (!value) return false;
  command.mutable_set_search()->set_slice_score(*value);
  return true;
}

bool SetLensName(Command& command, std::string_view text) {
  if (text.empty()) return false;
  command.mutable_set_lens()->set_name(std::string(text));
  return true;
}

bool SetPhotoInterval(Command& command, std::string_view text) {
  const auto value = ParseFloat(text);
  if (!value) return false;
  command.set_set_photo_interval_s(*value);
  return true;
}

}  // namespace

const std::vector<SettingKey>& SettingKeys() {
  static const std::vector<SettingKey> keys = {
      {"p", "[1] proportional gain", &SetFloat<&Command::mutable_set_gains, &Gains::set_p>},
      {"i", "[1/s] integral gain", &SetFloat<&Command::mutable_set_gains, &Gains::set_i>},
      {"d", "[s] derivative gain", &SetFloat<&Command::mutable_set_gains, &Gains::set_d>},
      {"dead_band", "[px] displacements this small are ignored",
       &SetFloat<&Command::mutable_set_gains, &Gains::set_dead_band_px>},
      {"rate_limit", "[deg/s] largest servo speed",
       &SetFloat<&Command::mutable_set_gains, &Gains::set_rate_limit_deg_per_s>},
      {"controller", "p | pid | predictive", &SetController},
      {"strategy", "all | h23 | h21 | h19 | h17 | h15 | pyr", &SetStrategy},
      {"sampling", "all | static | random", &SetSampling},
      {"random_fraction", "[1] share of patch pixels sampled, (0, 1]",
       &SetFloat<&Command::mutable_set_search, &SearchSettings::set_random_fraction>},
      {"patch_size", "[px] side of the square patch",
       &SetUint<&Command::mutable_set_search, &SearchSettings::set_patch_size_px>},
      {"slice_count", "[count] horizontal bands",
       &SetUint<&Command::mutable_set_search, &SearchSettings::set_slice_count>},
      {"axis", "x | y | both", &SetAxis},
      {"range", "[px] search range R: shifts in [-R, +R)",
       &SetUint<&Command::mutable_set_search, &SearchSettings::set_search_range_px>},
      {"subpixel", "on | off",
       &SetBool<&Command::mutable_set_search, &SearchSettings::set_subpixel>},
      {"channel", "green | rgb", &SetChannel},
      {"slice_score", "dc | dc_hysteresis | single_shot | fft", &SetSliceScore},
      {"hysteresis", "[px] hysteresis of the DC-with-hysteresis score",
       &SetFloat<&Command::mutable_set_search, &SearchSettings::set_dc_hysteresis_px>},
      {"gain", "[dB] camera gain",
       &SetFloat<&Command::mutable_set_camera, &CameraSettings::set_gain_db>},
      {"exposure", "[µs] camera exposure",
       &SetFloat<&Command::mutable_set_camera, &CameraSettings::set_exposure_us>},
      {"auto_exposure", "on | off",
       &SetBool<&Command::mutable_set_camera, &CameraSettings::set_auto_exposure>},
      {"lens", "lens profile name, e.g. 3.5mm", &SetLensName},
      {"focal_length", "[mm] lens focal length",
       &SetFloat<&Command::mutable_set_lens, &LensProfile::set_focal_length_mm>},
      {"pixel_pitch", "[µm] sensor pixel size",
       &SetFloat<&Command::mutable_set_lens, &LensProfile::set_pixel_pitch_um>},
      {"photo_interval", "[s] save a photo every N seconds, 0 = off", &SetPhotoInterval},
      {"video_fps", "[fps] largest video frame rate, 0 = video off",
       &SetFloat<&Command::mutable_set_video, &VideoSettings::set_fps>},
      {"jpeg_quality", "[1..100] video JPEG quality",
       &SetUint<&Command::mutable_set_video, &VideoSettings::set_jpeg_quality>},
      {"video_scale", "[1] video pixels per camera pixel, (0, 1]",
       &SetFloat<&Command::mutable_set_video, &VideoSettings::set_scale>},
  };
  return keys;
}

std::optional<Command> MakeSetCommand(std::string_view key, std::string_view value,
                                      std::string* error) {
  for (const SettingKey& entry : SettingKeys()) {
    if (entry.name != key) continue;
    Command command;
    if (entry.apply(command, value)) return command;
    if (error != nullptr) {
      *error = "cannot read '" + std::string(value) + "' as a value of " + std::string(key) + ": " +
               std::string(entry.help);
    }
    return std::nullopt;
  }
  if (error != nullptr) {
    *error = "unknown key '" + std::string(key) + "' (see kapfix-ctl set --help)";
  }
  return std::nullopt;
}

std::string SettingKeysHelp() {
  std::string text = "Keys:\n";
  for (const SettingKey& entry : SettingKeys()) {
    std::string name(entry.name);
    name.resize(std::max<std::size_t>(name.size() + 1, 17), ' ');
    text += "  " + name + std::string(entry.help) + "\n";
  }
  return text;
}

}  // namespace kapfix::ctl
