#include "agent/resume/resume_recorder.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <array>
#include <utility>

#include "agent/config/camera_config.hpp"

namespace kapfix::agent {
namespace {

using Case = kapfix::v1::Command::CommandCase;

// The order settings are stored in and applied back (the lens profiles come after these).
constexpr std::array<Case, 5> kSettingsOrder{
    kapfix::v1::Command::kSetGains, kapfix::v1::Command::kSetSearch,
    kapfix::v1::Command::kSetCamera, kapfix::v1::Command::kSetVideo,
    kapfix::v1::Command::kSetPhoto};

}  // namespace

ResumeRecorder::ResumeRecorder(ResumeStore& store, ModeEvents& next, const ResumeRecord& start,
                               std::string active_lens)
    : store_(store), next_(next), active_lens_(std::move(active_lens)) {
  for (const kapfix::v1::Command& command : start.settings) AddSettingLocked(command);
  mode_ = start.mode;
  slice_ = start.slice;
  reference_frame_ = start.reference_frame;
  reference_at_ = start.reference_at;
  writer_ = std::thread([this] { WriteLoop(); });
}

ResumeRecorder::~ResumeRecorder() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  writer_.join();
}

void ResumeRecorder::AddSettingLocked(const kapfix::v1::Command& command) {
  const Case kind = command.command_case();
  if (kind == kapfix::v1::Command::kSetLens) {
    kapfix::v1::LensProfile lens = command.set_lens();
    if (!lens.has_name()) lens.set_name(active_lens_);
    active_lens_ = lens.name();
    lens_switched_ = true;
    kapfix::v1::LensProfile optics = lens;
    optics.clear_name();
    if (optics.ByteSizeLong() != 0) {  // optics given (a present field serialises even at 0)
      kapfix::v1::Command& stored = lenses_[lens.name()];
      stored.mutable_set_lens()->MergeFrom(lens);
    }
    return;
  }
  if (std::find(kSettingsOrder.begin(), kSettingsOrder.end(), kind) == kSettingsOrder.end()) {
    return;  // not a setting
  }
  kapfix::v1::Command& stored = settings_[kind];
  if (kind == kapfix::v1::Command::kSetCamera) {
    // A fixed exposure and automatic exposure exclude each other: the agent's own merge.
    MergeCameraSettings(command.set_camera(), stored.mutable_set_camera());
    return;
  }
  // Only what the command carries is stored: absent fields keep the earlier commands' values.
  kapfix::v1::Command update = command;
  update.clear_header();
  stored.MergeFrom(update);
}

ResumeRecord ResumeRecorder::RecordLocked() const {
  ResumeRecord record;
  for (const Case kind : kSettingsOrder) {
    const auto found = settings_.find(kind);
    if (found != settings_.end()) record.settings.push_back(found->second);
  }
  for (const auto& [name, command] : lenses_) record.settings.push_back(command);
  if (lens_switched_) {
    kapfix::v1::Command in_use;
    in_use.mutable_set_lens()->set_name(active_lens_);
    record.settings.push_back(std::move(in_use));
  }
  record.mode = mode_;
  record.slice = slice_;
  record.reference_frame = reference_frame_;  // shared: fixate never writes into it again
  record.reference_at = reference_at_;
  return record;
}

void ResumeRecorder::ChangedLocked() {
  ++version_;
  wake_.notify_all();
}

void ResumeRecorder::OnSettingsApplied(const kapfix::v1::Command& command) {
  std::lock_guard lock(mutex_);
  AddSettingLocked(command);
  ChangedLocked();
}

void ResumeRecorder::Flush() {
  std::unique_lock lock(mutex_);
  const std::uint64_t wanted = version_;
  written_.wait(lock, [&] { return written_version_ >= wanted || stopping_; });
}

std::uint64_t ResumeRecorder::writes() const {
  std::lock_guard lock(mutex_);
  return writes_;
}

void ResumeRecorder::WriteLoop() {
  std::unique_lock lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stopping_ || version_ > written_version_; });
    if (version_ > written_version_) {
      const std::uint64_t version = version_;
      const ResumeRecord record = RecordLocked();
      lock.unlock();
      bool ok = true;
      try {
        store_.Save(record);
      } catch (const std::exception& e) {
        ok = false;
        spdlog::error("resume record not stored (a restart would not resume this): {}", e.what());
      }
      lock.lock();
      written_version_ = version;
      if (ok) ++writes_;
      written_.notify_all();
      continue;  // everything changed meanwhile is written before stopping
    }
    if (stopping_) return;
  }
}

void ResumeRecorder::OnModeChanged(AgentMode mode, int slice) {
  {
    std::lock_guard lock(mutex_);
    if (mode != mode_ || slice != slice_) {
      mode_ = mode;
      slice_ = slice;
      ChangedLocked();
    }
  }
  next_.OnModeChanged(mode, slice);
}

void ResumeRecorder::OnReferenceTaken(const cv::Mat& frame_bgr, const ServoTargets& servos) {
  {
    std::lock_guard lock(mutex_);
    reference_frame_ = frame_bgr;
    reference_at_ = servos;
    ChangedLocked();
  }
  next_.OnReferenceTaken(frame_bgr, servos);
}

void ResumeRecorder::OnSliceReport(const kapfix::v1::SliceReport& report) {
  next_.OnSliceReport(report);
}

void ResumeRecorder::OnPssReport(const kapfix::v1::PssReport& report) { next_.OnPssReport(report); }

void ResumeRecorder::OnCalibrationReport(const kapfix::v1::CalibrationReport& report,
                                         const std::optional<LensCalibration>& applied) {
  next_.OnCalibrationReport(report, applied);
}

void ResumeRecorder::OnFreeSwingRecorded(const std::string& path, const std::string& error) {
  next_.OnFreeSwingRecorded(path, error);
}

void ResumeRecorder::OnResumeEnded(bool resumed) { next_.OnResumeEnded(resumed); }

}  // namespace kapfix::agent
