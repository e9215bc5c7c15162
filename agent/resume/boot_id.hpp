#pragma once

#include <cstdint>

namespace kapfix::agent {

// A random 64-bit id drawn once per agent start (issue 14) and stamped in Header.boot_id of
// everything the agent sends: a station that sees another value from the same agent_id knows
// the agent restarted (a new session). Never 0, which means unset on the link.
std::uint64_t DrawBootId();

}  // namespace kapfix::agent
