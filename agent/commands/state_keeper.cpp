#include "agent/commands/state_keeper.hpp"

#include <spdlog/spdlog.h>

#include "agent/commands/settings_messages.hpp"
#include "agent/downlink/device_health_message.hpp"
#include "agent/downlink/telemetry_publisher.hpp"

namespace kapfix::agent {

StateKeeper::StateKeeper(AgentConfig settings, StreamSink& sink, bool simulated,
                         std::function<std::uint64_t()> photos_stored,
                         const CalibrationStore* calibrations)
    : settings_(std::make_shared<const AgentConfig>(std::move(settings))),
      sink_(sink),
      simulated_(simulated),
      photos_stored_(std::move(photos_stored)),
      calibrations_(calibrations) {}

std::shared_ptr<const AgentConfig> StateKeeper::settings() const {
  std::lock_guard lock(mutex_);
  return settings_;
}

void StateKeeper::SetSettings(AgentConfig settings) {
  {
    std::lock_guard lock(mutex_);
    settings_ = std::make_shared<const AgentConfig>(std::move(settings));
    ChangedLocked();
  }
  PublishState();
}

std::shared_ptr<const AgentConfig> StateKeeper::UpdateSettings(
    const std::function<bool(AgentConfig*, std::string*)>& change, std::string* error) {
  std::shared_ptr<const AgentConfig> updated;
  {
    std::lock_guard lock(mutex_);
    AgentConfig copy = *settings_;
    if (!change(&copy, error)) return nullptr;
    updated = std::make_shared<const AgentConfig>(std::move(copy));
    settings_ = updated;
    ChangedLocked();
  }
  PublishState();
  return updated;
}

kapfix::v1::AgentState StateKeeper::StateLocked() const {
  kapfix::v1::AgentState state;
  state.mutable_header()->set_agent_id(settings_->agent_id);
  state.set_mode(ToProto(mode_));
  FillSettings(*settings_, &state);
  state.set_slice(static_cast<std::uint32_t>(slice_));
  if (calibration_) *state.mutable_calibration() = *calibration_;
  if (last_slice_report_) *state.mutable_last_slice_report() = *last_slice_report_;
  if (last_pss_report_) *state.mutable_last_pss_report() = *last_pss_report_;
  state.set_simulated(simulated_);
  state.set_agent_version(KAPFIX_VERSION);  // the project version, from CMake
  state.set_version(version_);
  *state.mutable_camera_health() = ToProto(devices_.camera);
  *state.mutable_servo_health() = ToProto(devices_.servos);
  state.set_resumed(resumed_);
  return state;
}

kapfix::v1::AgentState StateKeeper::State() const {
  kapfix::v1::AgentState state;
  {
    std::lock_guard lock(mutex_);
    state = StateLocked();
  }
  // Outside the lock: it reads the disk.
  if (photos_stored_) state.set_photos_stored(photos_stored_());
  return state;
}

void StateKeeper::PublishState() {
  {
    std::lock_guard lock(mutex_);
    publish_wanted_ = true;
    if (publishing_) return;  // that thread publishes the newest state before it stops
    publishing_ = true;
  }
  // Clears publishing_ however the loop ends (a sink that throws must not stop all later
  // states).
  struct Done {
    StateKeeper& keeper;
    ~Done() {
      std::lock_guard lock(keeper.mutex_);
      keeper.publishing_ = false;
    }
  } done{*this};
  for (;;) {
    kapfix::v1::AgentState state;
    {
      std::lock_guard lock(mutex_);
      if (!publish_wanted_) return;
      publish_wanted_ = false;
      state = StateLocked();
    }
    // Outside the lock: it may read the disk.
    if (photos_stored_) state.set_photos_stored(photos_stored_());
    sink_.Publish(state);
  }
}

bool StateKeeper::RepublishSliceReport() {
  std::optional<kapfix::v1::SliceReport> report;
  {
    std::lock_guard lock(mutex_);
    report = last_slice_report_;
  }
  if (!report) return false;
  sink_.Publish(*report);
  return true;
}

void StateKeeper::OnDeviceHealth(const DevicesHealth& health) {
  {
    std::lock_guard lock(mutex_);
    if (devices_ == health) return;
    devices_ = health;
    ChangedLocked();
  }
  PublishState();
}

void StateKeeper::OnModeChanged(AgentMode mode, int slice) {
  {
    std::lock_guard lock(mutex_);
    mode_ = mode;
    slice_ = slice;
    ChangedLocked();
  }
  PublishState();
}

void StateKeeper::OnSliceReport(const kapfix::v1::SliceReport& report) {
  if (report.finished()) {
    std::lock_guard lock(mutex_);
    last_slice_report_ = report;
    ChangedLocked();
  }
  sink_.Publish(report);
}

void StateKeeper::OnPssReport(const kapfix::v1::PssReport& report) {
  if (report.finished()) {
    std::lock_guard lock(mutex_);
    last_pss_report_ = report;
    ChangedLocked();
  }
  sink_.Publish(report);
}

void StateKeeper::OnCalibrationReport(const kapfix::v1::CalibrationReport& report,
                                      const std::optional<LensCalibration>& applied) {
  if (report.finished()) {
    std::lock_guard lock(mutex_);
    calibration_ = report;
    ChangedLocked();
    if (applied) {
      AgentConfig calibrated = *settings_;
      calibrated.ApplyLensCalibration(report.lens_profile(), *applied);
      settings_ = std::make_shared<const AgentConfig>(std::move(calibrated));
    }
  }
  if (report.finished() && applied && calibrations_) {
    auto save = [store = calibrations_, report, calibration = *applied]() -> WorkQueue::Result {
      try {
        store->Save(report.lens_profile(), calibration, report);
        spdlog::info("calibration of lens {} stored", report.lens_profile());
      } catch (const std::exception& e) {
        spdlog::error("calibration of lens {} not stored: {}", report.lens_profile(), e.what());
      }
      return nullptr;
    };
    std::string refused;  // logged by the worker; the lens keeps the calibration until a restart
    if (!calibration_writer_) {
      save();
    } else if (!calibration_writer_->Post("calibration of lens " + report.lens_profile(),
                                          std::move(save), &refused)) {
      spdlog::error("calibration of lens {} not stored", report.lens_profile());
    }
  }
  sink_.Publish(report);
}

void StateKeeper::OnResumeEnded(bool resumed) {
  {
    std::lock_guard lock(mutex_);
    resumed_ = resumed;
    ChangedLocked();
  }
  PublishState();
}

void StateKeeper::OnFreeSwingRecorded(const std::string& path, const std::string& error) {
  if (error.empty()) {
    spdlog::info("free swing recording: {}", path);
  } else {
    spdlog::error("free swing recording failed: {}", error);
  }
}

}  // namespace kapfix::agent
