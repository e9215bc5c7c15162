#include "agent/config/simulation_config.hpp"

namespace kapfix::agent {

std::optional<MotionKind> ParseMotionKind(std::string_view text) {
  if (text == "kite") return MotionKind::kKite;
  if (text == "boat") return MotionKind::kBoat;
  return std::nullopt;
}

std::string_view ToString(MotionKind kind) {
  switch (kind) {
    case MotionKind::kKite:
      return "kite";
    case MotionKind::kBoat:
      return "boat";
  }
  return "?";
}

bool SimulationConfig::IsValid(std::string* error) const {
  // Whether the scene file can be read is checked where it is loaded, with the file's name
  // in the message.
  return world.IsValid(error);
}

}  // namespace kapfix::agent
