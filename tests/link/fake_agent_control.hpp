#pragma once

// Stands in for the agent's pipeline behind CommandServer: keeps an AgentState, applies
// the settings commands to it, records what it was asked, and can be told to refuse or to
// fail. With a StreamPublisher it also answers like the real agent on the streams: an SSP
// run publishes SliceReports, a photo is published in chunks.

#include <cstddef>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "agent/server/agent_control.hpp"
#include "agent/server/stream_publisher.hpp"

namespace kapfix::testing {

class FakeAgentControl : public kapfix::agent::AgentControl {
 public:
  // The photo the fake "takes": its name and bytes, sent in chunks of kPhotoChunk bytes.
  static constexpr const char* kPhotoName = "photo-0001.png";
  static constexpr std::size_t kPhotoChunk = 1000;
  static std::string PhotoBytes();
  static constexpr unsigned kRecommendedSlice = 3;

  FakeAgentControl();

  kapfix::v1::Reply Execute(const kapfix::v1::Command& command) override;
  kapfix::v1::AgentState State() const override;

  void SetPublisher(kapfix::agent::StreamPublisher* publisher);
  // Every later command is refused with this code and reason.
  void RefuseWith(kapfix::v1::ErrorCode code, std::string reason);
  // From now on it holds one stored photo (kPhotoName), which request_state with
  // resend_photos_since_us names in its reply and publishes again.
  void HoldStoredPhoto();
  // Every later Execute() throws std::runtime_error(what).
  void ThrowOnExecute(std::string what);

  std::vector<kapfix::v1::Command> commands() const;  // every command Execute() saw

 private:
  mutable std::mutex mutex_;
  kapfix::v1::AgentState state_;
  std::vector<kapfix::v1::Command> commands_;
  std::optional<kapfix::v1::Reply> refusal_;
  std::optional<std::string> failure_;
  kapfix::agent::StreamPublisher* publisher_ = nullptr;
  bool holds_stored_photo_ = false;
};

}  // namespace kapfix::testing
