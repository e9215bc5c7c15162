#pragma once

// The topics of the link (SPEC §5), declared once: a message travels as its topic (first
// frame; ZeroMQ SUB filters on it) and its serialized bytes. No topic is a prefix of another,
// so ZeroMQ's prefix subscription selects exactly one. Which kapfix.v1 type travels under
// which topic is TopicTable's (topic_table.hpp).

#include <string_view>

namespace kapfix::link {

inline constexpr std::string_view kTelemetryTopic = "telemetry";      // Telemetry
inline constexpr std::string_view kVideoTopic = "video";              // VideoFrame
inline constexpr std::string_view kSlicesTopic = "slices";            // SliceReport
inline constexpr std::string_view kPssTopic = "pss";                  // PssReport
inline constexpr std::string_view kCalibrationTopic = "calibration";  // CalibrationReport
inline constexpr std::string_view kPhotoTopic = "photo";              // Photo
inline constexpr std::string_view kLogTopic = "log";                  // Log
inline constexpr std::string_view kHeartbeatTopic = "heartbeat";      // Heartbeat, both ways
inline constexpr std::string_view kCommandTopic = "command";          // Command, station → agent
inline constexpr std::string_view kReplyTopic = "reply";              // Reply, agent → station
inline constexpr std::string_view kStateTopic = "state";              // AgentState

}  // namespace kapfix::link
