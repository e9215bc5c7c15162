#include "agent/commands/command_executor.hpp"

#include <spdlog/spdlog.h>

#include "agent/commands/settings_messages.hpp"
#include "agent/downlink/telemetry_publisher.hpp"

namespace kapfix::agent {
namespace {

kapfix::v1::Reply Ok() {
  kapfix::v1::Reply reply;
  reply.set_ok(true);
  return reply;
}

kapfix::v1::Reply Refuse(kapfix::v1::ErrorCode code, std::string reason) {
  kapfix::v1::Reply reply;
  reply.set_ok(false);
  reply.set_error(code);
  reply.set_reason(std::move(reason));
  return reply;
}

}  // namespace

CommandExecutor::CommandExecutor(CommandTargets targets) : targets_(std::move(targets)) {}

kapfix::v1::AgentState CommandExecutor::State() const { return targets_.state.State(); }

kapfix::v1::Reply CommandExecutor::SetMode(const kapfix::v1::SetMode& set_mode) {
  const std::optional<AgentMode> mode = FromProto(set_mode.mode());
  if (!mode) return Refuse(kapfix::v1::ERROR_CODE_OUT_OF_RANGE, "set_mode.mode: unknown mode");
  if (*mode == AgentMode::kRecordFreeSwing && !targets_.free_swing_recording_possible) {
    return Refuse(kapfix::v1::ERROR_CODE_STORAGE,
                  "free-swing recording needs a recordings folder (photos.dir)");
  }
  const auto settings = targets_.state.settings();
  SwingDeadline deadline{settings->search.swing_frames, settings->search.swing_seconds};
  if (set_mode.has_deadline_frames()) {
    deadline.frames = std::max(2, static_cast<int>(set_mode.deadline_frames()));
  }
  if (set_mode.has_deadline_s()) deadline.seconds = set_mode.deadline_s();
  targets_.modes.RequestMode(*mode, deadline);
  spdlog::info("command: mode {}", ToString(*mode));
  return Ok();
}

kapfix::v1::Reply CommandExecutor::ApplySettings(const kapfix::v1::Command& command) {
  std::string error;
  // Applied to the keeper's settings under its lock: a calibration that finishes meanwhile
  // is kept.
  const auto settings = targets_.state.UpdateSettings(
      [&command](AgentConfig* config, std::string* why) {
        return ApplySettingsCommand(command, config, why);
      },
      &error);
  if (!settings) return Refuse(kapfix::v1::ERROR_CODE_OUT_OF_RANGE, error);
  switch (command.command_case()) {
    case kapfix::v1::Command::kSetCamera:
      if (targets_.apply_camera) targets_.apply_camera(settings->camera.settings);
      break;
    case kapfix::v1::Command::kSetVideo:
      targets_.video.SetSettings(settings->video);
      break;
    case kapfix::v1::Command::kSetPhoto:
      targets_.photos.SetSettings(settings->photo);
      break;
    default:
      targets_.modes.RequestSettings(settings);
      break;
  }
  return Ok();
}

kapfix::v1::Reply CommandExecutor::Execute(const kapfix::v1::Command& command) {
  if (IsSettingsCommand(command)) return ApplySettings(command);
  switch (command.command_case()) {
    case kapfix::v1::Command::kSetMode:
      return SetMode(command.set_mode());
    case kapfix::v1::Command::kSelectSlice:
      targets_.modes.RequestSlice(static_cast<int>(command.select_slice()));
      return Ok();
    case kapfix::v1::Command::kTakePhoto: {
      std::string error;
      std::string file_name;
      if (!targets_.photos.Request(command.take_photo().note(), &error, &file_name)) {
        return Refuse(kapfix::v1::ERROR_CODE_STORAGE, error);
      }
      kapfix::v1::Reply reply = Ok();
      reply.set_photo_file_name(file_name);
      return reply;
    }
    case kapfix::v1::Command::kRequestState: {
      const kapfix::v1::RequestState& request = command.request_state();
      kapfix::v1::Reply reply = Ok();
      if (request.resend_photos_since_us() > 0) {
        for (std::string& name : targets_.photos.Resend(request.resend_photos_since_us())) {
          reply.add_photos_resent(std::move(name));
        }
      }
      if (request.resend_slice_report()) targets_.state.RepublishSliceReport();
      *reply.mutable_state() = targets_.state.State();
      return reply;
    }
    default:
      return Refuse(kapfix::v1::ERROR_CODE_UNKNOWN_COMMAND, "command not known to this agent");
  }
}

}  // namespace kapfix::agent
