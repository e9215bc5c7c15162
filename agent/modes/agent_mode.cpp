#include "agent/modes/agent_mode.hpp"

#include <array>
#include <utility>

namespace kapfix::agent {
namespace {

constexpr std::array<std::pair<AgentMode, std::string_view>, 7> kNames{{
    {AgentMode::kIdle, "idle"},
    {AgentMode::kCalibrate, "calibrate"},
    {AgentMode::kPss, "pss"},
    {AgentMode::kSsp, "ssp"},
    {AgentMode::kFixate, "fixate"},
    {AgentMode::kFollow, "follow"},
    {AgentMode::kRecordFreeSwing, "record"},
}};

}  // namespace

std::string_view ToString(AgentMode mode) {
  for (const auto& [m, name] : kNames) {
    if (m == mode) return name;
  }
  return "unknown";
}

std::optional<AgentMode> ParseAgentMode(std::string_view text) {
  for (const auto& [m, name] : kNames) {
    if (name == text) return m;
  }
  return std::nullopt;
}

}  // namespace kapfix::agent
