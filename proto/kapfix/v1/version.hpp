#pragma once

#include <cstdint>

namespace kapfix::v1 {

// The link protocol version this build speaks (Header.protocol_version). Bump it, together
// with a new package kapfix.v2, only for a change old peers cannot read; compatible
// additions to kapfix.v1 keep it.
constexpr std::uint32_t kProtocolVersion = 1;

}  // namespace kapfix::v1
