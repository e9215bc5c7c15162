#pragma once

#include <functional>
#include <memory>
#include <mutex>
#include <optional>

#include "agent/commands/calibration_store.hpp"
#include "agent/config/agent_config.hpp"
#include "agent/modes/mode_events.hpp"
#include "agent/pipeline/device_health.hpp"
#include "agent/server/stream_sink.hpp"
#include "agent/worker/work_queue.hpp"
#include "kapfix/v1/state.pb.h"

namespace kapfix::agent {

// The agent's settings and latest results, as a station sees them (AgentState): the one copy
// the command side changes and the modes report into. Publishes the reports as they come and
// the AgentState after every change, so a station that (re)connects is resynchronised by one
// request_state. Thread-safe.
//
// States are published in version order: every change raises AgentState.version, and one
// thread at a time publishes, always the newest state. A thread that wants a state published
// while another is publishing does not wait: it leaves the newest state to that thread, which
// publishes again before it stops (so the control thread never waits on a command's publish,
// and an older snapshot can never be the last one sent).
class StateKeeper : public ModeEvents {
 public:
  // `photos_stored` counts the photos on the agent's disk when a state is made.
  // `calibrations`: where finished calibrations are kept per lens profile; may be null.
  StateKeeper(AgentConfig settings, StreamSink& sink, bool simulated,
              std::function<std::uint64_t()> photos_stored,
              const CalibrationStore* calibrations = nullptr);

  // Calibrations are stored by `worker` (a disk write with fsync), not on the control thread
  // that reports them; without one, within OnCalibrationReport. `worker` must outlive this.
  void StoreCalibrationsOn(WorkQueue* worker) { calibration_writer_ = worker; }

  // The settings now: an immutable snapshot that stays as it is while the keeper moves on.
  std::shared_ptr<const AgentConfig> settings() const;
  void SetSettings(AgentConfig settings);  // must be IsValid; publishes the new state
  // Applies `change` to a copy of the settings under the keeper's lock, so that no other
  // change (a calibration finishing on the control thread) is lost in between; stores and
  // publishes the result when `change` returns true. The new snapshot, or nullptr with
  // `change`'s reason in `error`.
  std::shared_ptr<const AgentConfig> UpdateSettings(
      const std::function<bool(AgentConfig*, std::string*)>& change, std::string* error);
  kapfix::v1::AgentState State() const;
  // Publishes the current state (again, with the same version when nothing changed).
  void PublishState();
  // Publishes the latest SliceReport again (request_state.resend_slice_report); false if SSP
  // never ran.
  bool RepublishSliceReport();

  // The camera's and servos' health (the pipeline's on_health): a change is a new state,
  // published at once; the same health again changes nothing.
  void OnDeviceHealth(const DevicesHealth& health);

  void OnModeChanged(AgentMode mode, int slice) override;
  void OnSliceReport(const kapfix::v1::SliceReport& report) override;
  void OnPssReport(const kapfix::v1::PssReport& report) override;
  void OnCalibrationReport(const kapfix::v1::CalibrationReport& report,
                           const std::optional<LensCalibration>& applied) override;
  void OnFreeSwingRecorded(const std::string& path, const std::string& error) override;
  void OnResumeEnded(bool resumed) override;  // AgentState.resumed (issue 14)

 private:
  kapfix::v1::AgentState StateLocked() const;
  // Under mutex_: every change of what State() reports raises the version.
  void ChangedLocked() { ++version_; }

  mutable std::mutex mutex_;
  std::shared_ptr<const AgentConfig> settings_;  // replaced, never changed in place
  StreamSink& sink_;
  bool simulated_;
  std::function<std::uint64_t()> photos_stored_;
  const CalibrationStore* calibrations_;
  WorkQueue* calibration_writer_ = nullptr;
  AgentMode mode_ = AgentMode::kIdle;
  int slice_ = 0;
  std::optional<kapfix::v1::SliceReport> last_slice_report_;
  std::optional<kapfix::v1::PssReport> last_pss_report_;
  std::optional<kapfix::v1::CalibrationReport> calibration_;
  DevicesHealth devices_;
  bool resumed_ = false;         // this run came back fixating the view it stored before a restart
  std::uint64_t version_ = 1;    // [count] of the state as it is now
  bool publishing_ = false;      // a thread is in PublishState's loop
  bool publish_wanted_ = false;  // a state was asked for since that thread's last snapshot
};

}  // namespace kapfix::agent
