#include "agent/config_file/lens_profiles.hpp"

#include <algorithm>

#include "agent/config/config_reader.hpp"
#include "agent/config/options_from_settings.hpp"
#include "agent/config_file/json_message.hpp"
#include "kapfix/v1/settings.pb.h"
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {
namespace {

// The profile's keys that are no settings (kapfix.v1.LensProfile has no such field).
constexpr const char* kDegPerPxKeys[] = {"deg_per_px_pan", "deg_per_px_tilt"};
// The focal length's key in files written before the profile was the settings message.
constexpr const char* kOlderFocalKey = "focal_mm";

std::string ReadLensProfile(const nlohmann::json& entry, const std::string& path,
                            LensProfile* profile) {
  ConfigReader reader(entry, path);
  reader.Read(kDegPerPxKeys[0], &profile->deg_per_px_pan);
  reader.Read(kDegPerPxKeys[1], &profile->deg_per_px_tilt);
  if (!reader.ok()) return reader.error();
  nlohmann::json optics = nlohmann::json::object();
  for (const auto& [key, value] : entry.items()) {
    if (std::find(std::begin(kDegPerPxKeys), std::end(kDegPerPxKeys), key) !=
        std::end(kDegPerPxKeys)) {
      continue;
    }
    optics[key == kOlderFocalKey ? "focal_length_mm" : key] = value;
  }
  kapfix::v1::LensProfile message;
  std::string reason = ReadJsonMessage(optics, path, &message);
  if (reason.empty()) reason = kapfix::v1::CheckSettings(message, path);
  if (reason.empty()) CopySettings(message, profile, &reason);
  return reason;
}

}  // namespace

bool ReadLensProfiles(const nlohmann::json& lenses, AgentConfig* config, std::string* error) {
  auto fail = [error](const std::string& reason) {
    if (error) *error = reason;
    return false;
  };
  if (!lenses.is_array()) return fail("lenses: must be an array, got " + lenses.dump());
  // A "lenses" list replaces the default profile rather than adding to it.
  config->lenses.clear();
  for (std::size_t i = 0; i < lenses.size(); ++i) {
    const std::string path = "lenses[" + std::to_string(i) + "]";
    const std::string reason = ReadLensProfile(lenses[i], path, &config->lenses.emplace_back());
    if (!reason.empty()) return fail(reason);
  }
  // The first profile is fitted unless settings.lens (read after) names another.
  if (!config->lenses.empty() &&
      std::none_of(config->lenses.begin(), config->lenses.end(),
                   [config](const LensProfile& p) { return p.name == config->lens; })) {
    config->lens = config->lenses.front().name;
  }
  return true;
}

}  // namespace kapfix::agent
