#pragma once

// kapfix-ctl's printed lines: stable "key=value" words, one record per line, so that scripts
// can grep and split them (the exit code says whether to trust them).

#include <string>

#include "kapfix/v1/slices.pb.h"
#include "kapfix/v1/state.pb.h"
#include "kapfix/v1/telemetry.pb.h"

namespace kapfix::ctl {

// Several lines: mode, the devices ("camera: ok", "servos: waiting reason=…"), slice, then one
// line per settings group ("gains: p=0.8 …").
std::string StateText(const kapfix::v1::AgentState& state);

// One line: "telemetry seq=… frame=… mode=fixate dx=… dy=… confidence=… lock_lost=0 …".
std::string TelemetryText(const kapfix::v1::Telemetry& telemetry);

// One line of progress, or on the final report one line per slice and the recommendation.
std::string SliceReportText(const kapfix::v1::SliceReport& report);

// "fixate" for MODE_FIXATE: an enum value's name without its type prefix, lower case.
std::string ModeWord(kapfix::v1::Mode mode);
// "ok", "waiting", "lost"; "unknown" from an agent that does not report it.
std::string DeviceHealthWord(kapfix::v1::DeviceStatus status);

}  // namespace kapfix::ctl
