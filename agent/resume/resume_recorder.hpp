#pragma once

#include <condition_variable>
#include <cstdint>
#include <map>
#include <mutex>
#include <string>
#include <thread>

#include "agent/modes/mode_events.hpp"
#include "agent/resume/resume_record.hpp"
#include "agent/resume/resume_store.hpp"

namespace kapfix::agent {

// Keeps the ResumeRecord of this run up to date and on disk (issue 14), on change only:
// a settings command that was carried out (OnSettingsApplied, from RecordingControl), a mode
// or slice change and a new fixation reference (as the ModeEvents in front of the state
// keeper, to which it passes every event on). Writes on a thread of its own, the newest
// record only, so neither the control thread nor the command thread waits for the disk; a
// write that fails is logged and retried with the next change.
class ResumeRecorder : public ModeEvents {
 public:
  // `next`: where the events go on to. `start`: what this run resumed from (empty on a fresh
  // start), kept until something replaces it. `active_lens`: the lens profile in use, which
  // a set_lens without a name is about.
  ResumeRecorder(ResumeStore& store, ModeEvents& next, const ResumeRecord& start,
                 std::string active_lens);
  ~ResumeRecorder() override;  // writes what is pending, then stops
  ResumeRecorder(const ResumeRecorder&) = delete;
  ResumeRecorder& operator=(const ResumeRecorder&) = delete;

  // Any thread: a settings command was carried out. Partial updates add up (set_gains p then
  // set_gains i keeps both); set_lens is kept per lens profile, with the profile in use.
  void OnSettingsApplied(const kapfix::v1::Command& command);
  // Waits until every change made so far is written (or its write failed and was logged).
  void Flush();
  std::uint64_t writes() const;  // [count] records written

  void OnModeChanged(AgentMode mode, int slice) override;
  void OnSliceReport(const kapfix::v1::SliceReport& report) override;
  void OnPssReport(const kapfix::v1::PssReport& report) override;
  void OnCalibrationReport(const kapfix::v1::CalibrationReport& report,
                           const std::optional<LensCalibration>& applied) override;
  void OnFreeSwingRecorded(const std::string& path, const std::string& error) override;
  void OnReferenceTaken(const cv::Mat& frame_bgr, const ServoTargets& servos) override;
  void OnResumeEnded(bool resumed) override;

 private:
  void AddSettingLocked(const kapfix::v1::Command& command);
  ResumeRecord RecordLocked() const;
  void ChangedLocked();
  void WriteLoop();

  ResumeStore& store_;
  ModeEvents& next_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;     // a change or stop, for the writer
  std::condition_variable written_;  // a write ended, for Flush
  // The settings, by command (set_lens apart: per profile, then the profile in use).
  std::map<int, kapfix::v1::Command> settings_;
  std::map<std::string, kapfix::v1::Command> lenses_;
  std::string active_lens_;
  bool lens_switched_ = false;  // a set_lens came: the profile in use is a setting too
  AgentMode mode_ = AgentMode::kIdle;
  int slice_ = 0;
  cv::Mat reference_frame_;
  ServoTargets reference_at_;
  std::uint64_t version_ = 0;  // [count] changes
  std::uint64_t written_version_ = 0;
  std::uint64_t writes_ = 0;
  bool stopping_ = false;
  std::thread writer_;
};

}  // namespace kapfix::agent
