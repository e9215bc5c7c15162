#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

#include "common/sim/world_options.hpp"

namespace kapfix::agent {

enum class MotionKind {
  kKite,  // damped pendulum along X with gusts (SPEC §3)
  kBoat,  // roll along Y with waves
};

std::optional<MotionKind> ParseMotionKind(std::string_view text);  // kite|boat
std::string_view ToString(MotionKind kind);

// The "simulation" section: what the simulated camera and servos show (SPEC §3); used when
// a backend is "sim" or with --sim. Defaults: resources/README.md.
struct SimulationConfig {
  std::string scene;  // scene photo; "" = the agent's built-in default scene
  MotionKind motion = MotionKind::kKite;
  std::uint32_t seed = 1;  // every random part of the simulation derives from it
  bool gusts = true;       // kite only: random gust impulses
  // The field's disturbances (kapfix-agent --sim --world …, issue 9); nominal by default.
  // Its gusts override `gusts` when it is not the nominal periodic model.
  WorldOptions world;

  bool IsValid(std::string* error) const;
};

}  // namespace kapfix::agent
