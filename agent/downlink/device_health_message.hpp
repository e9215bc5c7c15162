#pragma once

#include "agent/pipeline/device_health.hpp"
#include "kapfix/v1/types.pb.h"

namespace kapfix::agent {

// kapfix.v1.DeviceHealth of AgentState and Telemetry.
kapfix::v1::DeviceHealth ToProto(const DeviceHealth& health);

}  // namespace kapfix::agent
