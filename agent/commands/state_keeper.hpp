#pragma once

#include <functional>
#include <mutex>
#include <optional>

#include "agent/commands/calibration_store.hpp"
#include "agent/config/agent_config.hpp"
#include "agent/modes/mode_events.hpp"
#include "agent/server/stream_sink.hpp"
#include "kapfix/v1/state.pb.h"

namespace kapfix::agent {

// The agent's settings and latest results, as a station sees them (AgentState): the one copy
// the command side changes and the modes report into. Publishes the reports as they come and
// the AgentState after every change, so a station that (re)connects is resynchronised by one
// request_state. Thread-safe.
class StateKeeper : public ModeEvents {
 public:
  // `photos_stored` counts the photos on the agent's disk when a state is made.
  // `calibrations`: where finished calibrations are kept per lens profile; may be null.
  StateKeeper(AgentConfig settings, StreamSink& sink, bool simulated,
              std::function<std::uint64_t()> photos_stored,
              const CalibrationStore* calibrations = nullptr);

  AgentConfig settings() const;
  void SetSettings(AgentConfig settings);  // must be IsValid; publishes the new state
  kapfix::v1::AgentState State() const;
  void PublishState();
  // Publishes the latest SliceReport again (request_state.resend_slice_report); false if SSP
  // never ran.
  bool RepublishSliceReport();

  void OnModeChanged(AgentMode mode, int slice) override;
  void OnSliceReport(const kapfix::v1::SliceReport& report) override;
  void OnPssReport(const kapfix::v1::PssReport& report) override;
  void OnCalibrationReport(const kapfix::v1::CalibrationReport& report,
                           const std::optional<LensCalibration>& applied) override;
  void OnFreeSwingRecorded(const std::string& path, const std::string& error) override;

 private:
  kapfix::v1::AgentState StateLocked() const;

  mutable std::mutex mutex_;
  AgentConfig settings_;
  StreamSink& sink_;
  bool simulated_;
  std::function<std::uint64_t()> photos_stored_;
  const CalibrationStore* calibrations_;
  AgentMode mode_ = AgentMode::kIdle;
  int slice_ = 0;
  std::optional<kapfix::v1::SliceReport> last_slice_report_;
  std::optional<kapfix::v1::PssReport> last_pss_report_;
  std::optional<kapfix::v1::CalibrationReport> calibration_;
};

}  // namespace kapfix::agent
