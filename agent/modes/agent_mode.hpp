#pragma once

#include <optional>
#include <string_view>

namespace kapfix::agent {

// What the agent is doing (SPEC §4); kapfix.v1.Mode on the link.
enum class AgentMode {
  kIdle,             // servos hold, nothing measured
  kCalibrate,        // servos moved by known amounts, deg/px fitted (SPEC §2.7)
  kPss,              // patch size selection over a free swing, servos holding (SPEC §2.5)
  kSsp,              // slice selection over a free swing, servos holding (SPEC §2.6)
  kFixate,           // every frame against the stored reference, servos on
  kFollow,           // every frame against the previous one (a moving boat), servos on
  kRecordFreeSwing,  // servos holding, the swing's displacement graph written to disk
};

std::string_view ToString(AgentMode mode);
// idle|calibrate|pss|ssp|fixate|follow|record
std::optional<AgentMode> ParseAgentMode(std::string_view text);

// A free-swing process (PSS, SSP, recording) stops with what it has after this many frames or
// seconds, whichever comes first.
struct SwingDeadline {
  int frames = 300;       // [frames] ≥ 2
  double seconds = 20.0;  // [s] of camera time, > 0
};

}  // namespace kapfix::agent
