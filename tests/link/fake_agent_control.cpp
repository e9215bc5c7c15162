#include "tests/link/fake_agent_control.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "kapfix/v1/photo.pb.h"
#include "kapfix/v1/slices.pb.h"

namespace kapfix::testing {
namespace {

constexpr unsigned kSlices = 9;

void PublishSlices(kapfix::agent::StreamPublisher& publisher) {
  kapfix::v1::SliceReport progress;
  progress.set_progress_done(50);
  progress.set_progress_total(100);
  publisher.Publish(progress);
  kapfix::v1::SliceReport report;
  for (unsigned i = 1; i <= kSlices; ++i) {
    auto* slice = report.add_slices();
    slice->set_index(i);
    slice->set_dc(i == FakeAgentControl::kRecommendedSlice ? 21 : 100 + i);
    slice->set_rank(i == FakeAgentControl::kRecommendedSlice ? 1 : 0);
  }
  report.set_recommended_slice(FakeAgentControl::kRecommendedSlice);
  report.set_progress_done(100);
  report.set_progress_total(100);
  report.set_finished(true);
  publisher.Publish(report);
}

void PublishPhoto(kapfix::agent::StreamPublisher& publisher) {
  const std::string bytes = FakeAgentControl::PhotoBytes();
  for (std::size_t offset = 0; offset < bytes.size(); offset += FakeAgentControl::kPhotoChunk) {
    kapfix::v1::Photo chunk;
    chunk.mutable_metadata()->set_file_name(FakeAgentControl::kPhotoName);
    chunk.mutable_metadata()->set_format("png");
    chunk.mutable_metadata()->set_shutter(kapfix::v1::SHUTTER_BEST_PHASE);  // issue 13's fields
    chunk.mutable_metadata()->set_view_speed_px_per_frame(0.75F);
    chunk.set_offset_bytes(offset);
    chunk.set_total_bytes(bytes.size());
    chunk.set_data(bytes.substr(offset, FakeAgentControl::kPhotoChunk));
    publisher.Publish(chunk);
  }
}

}  // namespace

std::string FakeAgentControl::PhotoBytes() {
  std::string bytes(2500, '\0');
  for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<char>(i * 7 % 251);
  return bytes;
}

FakeAgentControl::FakeAgentControl() {
  state_.set_mode(kapfix::v1::MODE_IDLE);
  state_.set_frame_width_px(640);
  state_.set_frame_height_px(480);
  state_.set_simulated(true);
  state_.set_agent_version("0.1.0-fake");
  state_.mutable_search()->set_strategy("h23");
  state_.mutable_search()->set_slice_count(kSlices);
  state_.mutable_search()->set_patch_size_px(100);
  state_.mutable_gains()->set_controller(kapfix::v1::CONTROLLER_KIND_PID);
  state_.mutable_gains()->set_p(0.8F);
}

kapfix::v1::Reply FakeAgentControl::Execute(const kapfix::v1::Command& command) {
  kapfix::agent::StreamPublisher* publisher = nullptr;
  kapfix::v1::Reply reply;
  {
    const std::lock_guard lock(mutex_);
    commands_.push_back(command);
    if (failure_) throw std::runtime_error(*failure_);
    if (refusal_) return *refusal_;
    publisher = publisher_;
    switch (command.command_case()) {
      case kapfix::v1::Command::kSetMode:
        state_.set_mode(command.set_mode().mode());
        break;
      case kapfix::v1::Command::kSelectSlice:
        state_.set_slice(command.select_slice());
        break;
      case kapfix::v1::Command::kSetGains:
        state_.mutable_gains()->MergeFrom(command.set_gains());
        break;
      case kapfix::v1::Command::kSetSearch:
        state_.mutable_search()->MergeFrom(command.set_search());
        break;
      case kapfix::v1::Command::kRequestState:
        *reply.mutable_state() = state_;
        // Its stored photo counts as taken after any time asked for.
        if (holds_stored_photo_ && command.request_state().resend_photos_since_us() > 0) {
          reply.add_photos_resent(kPhotoName);
        }
        break;
      default:
        break;
    }
  }
  // Published outside the lock, as the real agent's pipeline does from its own threads.
  if (publisher != nullptr && command.has_set_mode() &&
      command.set_mode().mode() == kapfix::v1::MODE_SSP) {
    PublishSlices(*publisher);
  }
  if (publisher != nullptr && (command.has_take_photo() || reply.photos_resent_size() > 0)) {
    PublishPhoto(*publisher);
  }
  reply.set_ok(true);
  return reply;
}

kapfix::v1::AgentState FakeAgentControl::State() const {
  const std::lock_guard lock(mutex_);
  return state_;
}

void FakeAgentControl::SetPublisher(kapfix::agent::StreamPublisher* publisher) {
  const std::lock_guard lock(mutex_);
  publisher_ = publisher;
}

void FakeAgentControl::RefuseWith(kapfix::v1::ErrorCode code, std::string reason) {
  const std::lock_guard lock(mutex_);
  refusal_.emplace();
  refusal_->set_ok(false);
  refusal_->set_error(code);
  refusal_->set_reason(std::move(reason));
}

void FakeAgentControl::HoldStoredPhoto() {
  const std::lock_guard lock(mutex_);
  holds_stored_photo_ = true;
}

void FakeAgentControl::ThrowOnExecute(std::string what) {
  const std::lock_guard lock(mutex_);
  failure_ = std::move(what);
}

std::vector<kapfix::v1::Command> FakeAgentControl::commands() const {
  const std::lock_guard lock(mutex_);
  return commands_;
}

}  // namespace kapfix::testing
