#include "agent/config_file/agent_config_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "agent/config_file/json_line.hpp"
#include "agent/config_file/lens_profiles.hpp"
#include "agent/config_file/settings_object.hpp"

namespace kapfix::agent {
namespace {

// The reason, and the line of the field it names (0: none).
struct ConfigProblem {
  std::string reason;
  int line = 0;
};

bool Parse(const std::string& json_text, AgentConfig* config, ConfigProblem* problem) {
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(json_text);
  } catch (const nlohmann::json::parse_error& e) {
    // e.what() is "[json.exception.parse_error.101] parse error at line L, column C: …".
    std::string what = e.what();
    const std::size_t tag_end = what.find("] ");
    if (tag_end != std::string::npos) what = what.substr(tag_end + 2);
    problem->reason = "invalid JSON: " + what;
    return false;
  }
  AgentConfig parsed;
  std::string reason;
  const bool ok =
      ReadAgentDevices(json, &parsed, &reason) &&
      (!json.contains("lenses") || ReadLensProfiles(json.at("lenses"), &parsed, &reason)) &&
      (!json.contains("settings") || ApplySettingsObject(json.at("settings"), &parsed, &reason)) &&
      parsed.IsValid(&reason);
  if (!ok) {
    problem->line = JsonLineOf(json_text, FieldOfReason(reason));
    problem->reason = std::move(reason);
    return false;
  }
  *config = std::move(parsed);
  return true;
}

}  // namespace

bool ParseAgentConfig(const std::string& json_text, AgentConfig* config, std::string* error) {
  ConfigProblem problem;
  if (Parse(json_text, config, &problem)) return true;
  if (error) {
    *error = problem.line > 0 ? "line " + std::to_string(problem.line) + ": " + problem.reason
                              : problem.reason;
  }
  return false;
}

bool LoadAgentConfig(const std::string& path, AgentConfig* config, std::string* error) {
  std::ifstream file(path, std::ios::binary);
  if (!file) {
    if (error) *error = path + ": cannot read (" + std::strerror(errno) + ")";
    return false;
  }
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) {
    if (error) *error = path + ": read error";
    return false;
  }
  ConfigProblem problem;
  if (Parse(text.str(), config, &problem)) return true;
  if (error) {
    *error = path + (problem.line > 0 ? ":" + std::to_string(problem.line) : std::string()) + ": " +
             problem.reason;
  }
  return false;
}

}  // namespace kapfix::agent
