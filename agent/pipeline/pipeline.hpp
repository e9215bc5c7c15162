#pragma once

#include <atomic>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "agent/capture/frame_source.hpp"
#include "agent/modes/frame_processor.hpp"
#include "agent/pipeline/device_health.hpp"
#include "agent/pipeline/latest_frame_slot.hpp"
#include "agent/pipeline/servo_commander.hpp"
#include "agent/pipeline/step_observer.hpp"
#include "agent/pipeline/watchdog.hpp"
#include "agent/servo/limited_servo_driver.hpp"
#include "agent/worker/work_queue.hpp"
#include "common/control/servo_belief.hpp"
#include "common/fixation/fixation_loop.hpp"

namespace kapfix::agent {

struct PipelineOptions {
  // Frames to process, then stop; 0 = until Stop() or the camera fails.
  std::uint64_t frames = 0;
  // Simulation: the capture thread grabs frame t + 1 only after the control thread finished
  // frame t, so no frame is dropped and a flight is deterministic whatever the machine's
  // speed. Hardware runs free: the camera sets the pace and stale frames are dropped.
  bool lock_step = false;
  int watchdog_ms = 500;  // [ms] servos park when no control step completed for this long
  WatchdogClock watchdog_clock = std::chrono::steady_clock::now;  // a test's own time
  // [frames] from the capture of a frame to the first frame that shows the command sent for
  // it (1 + the servos' latency). The angles a frame was seen through are taken as the
  // command sent that many frames earlier (park before the first command).
  int actuation_delay_frames = 2;
  // What the loop believes the servos showed while a frame was exposed: told every command
  // sent (Sent) and every frame processed (Expose), shared with the fixation controller that
  // resolves it when the latency jitters. None: the pipeline makes one with the fixed
  // actuation_delay_frames.
  std::shared_ptr<ServoBelief> servo_belief;
  double default_frame_period_s = 1.0 / 30;  // [s] dt for the first frame
  // A lost camera (Grab fails): the servos hold where they are (the watchdog does not count
  // the outage as a stall), Open is retried after retry_initial_ms, doubling up to
  // retry_max_ms, until it succeeds or Stop(); then the flight resumes. Off: a lost camera
  // ends the run.
  // The same back-off reopens a failed servo driver (ServoCommander); that one always retries,
  // each attempt a job on `worker` (the agent's; none: a queue of the pipeline's own).
  bool reconnect_camera = true;
  int retry_initial_ms = 100;  // [ms]
  int retry_max_ms = 5000;     // [ms]
  std::shared_ptr<WorkQueue> worker;
  // Start-up that waits for hardware: a camera or servo driver that did not open is retried
  // with the same back-off from the start (said in the log), rather than ending the run. The
  // servos are not moved before a camera frame arrives and the driver is open.
  bool camera_open = true;
  bool servos_open = true;
  // Why the camera / the servo driver did not open at start (the health's reason).
  std::string camera_error;
  std::string servos_error;
  // The operator's camera settings: applied on the capture thread before the first Grab and
  // after every reopen of the camera; SetCameraSettings replaces them. A setting the camera
  // refuses is said in the log (FrameSource::Apply's line) and the flight goes on.
  kapfix::v1::CameraSettings camera_settings;
  // Called on every control step and every reconnect wait: the service manager's watchdog.
  std::function<void()> on_alive;
  // Called on every change of the devices' health (the camera's from the capture thread, the
  // servos' from the control thread), one call at a time and in the order of the changes: for
  // the service manager's status and the AgentState. A retry that fails again is no change.
  // Must not call Pipeline::health() (it runs under the lock that guards it).
  std::function<void(const DevicesHealth&)> on_health;
  // Between the steps of the final park (one frame period at the rate limit each); default:
  // sleep default_frame_period_s. Simulated time needs no wait.
  std::function<void()> park_wait;
  // Simulation truth for telemetry: the view's residual offset of a frame, by index.
  std::function<std::optional<cv::Point2d>(std::uint64_t)> view_offset;
};

struct PipelineStats {
  std::uint64_t processed = 0;          // control steps run
  std::uint64_t dropped = 0;            // stale frames replaced before control took them
  std::uint64_t grab_errors = 0;        // failed Grabs
  std::uint64_t camera_reconnects = 0;  // outages the camera came back from
  std::uint64_t servo_errors = 0;       // refused or failed servo commands
  std::uint64_t servo_outages = 0;      // servo driver failures
  std::uint64_t servo_recoveries = 0;   // outages the servo driver came back from
  std::uint64_t watchdog_stalls = 0;
  double wall_s = 0;  // [s] from start to the last step
  std::string error;  // why the run ended early, if it did
};

// The agent's threads (SPEC §4): a capture thread hands the latest frame to a control thread,
// which runs the FrameProcessor (the first frame becomes the reference) and commands the
// servos through LimitedServoDriver; a Watchdog parks them when the control loop stalls; every
// step is recorded. The pipeline does not know which camera or servos it drives.
class Pipeline {
 public:
  // The source and driver need not be open (PipelineOptions camera_open, servos_open). Source,
  // driver, processor and recorder must outlive the pipeline.
  Pipeline(FrameSource& source, LimitedServoDriver& servos, FrameProcessor& processor,
           std::vector<StepObserver*> observers, PipelineOptions options);

  // Runs until options.frames are processed, Stop(), or a camera failure; then slews the
  // servos to park at the rate limit and waits until they are there (if they were ever
  // moved). Blocks; call once.
  PipelineStats Run();
  // From any thread: ends Run soon.
  void Stop() { stop_ = true; }
  // From any thread: the camera settings from now on (the whole message, not a change). The
  // capture thread applies them before its next Grab, because camera drivers are not safe to
  // call from two threads, and again after a reconnect.
  void SetCameraSettings(const kapfix::v1::CameraSettings& settings);
  // From any thread: whether the camera and the servo driver are there now (also carried by
  // every step's TelemetryRecord).
  DevicesHealth health() const;

 private:
  void CaptureThread(PipelineStats* stats, const std::function<void()>& on_outage);
  // Retries Open with back-off until it succeeds (true) or Stop() (false).
  bool Reconnect(const std::string& reason, bool at_start);
  void ControlThread(PipelineStats* stats, const std::function<void()>& kick);
  void SetCameraHealth(DeviceHealth health);
  void SetServoHealth(DeviceHealth health);

  FrameSource& source_;
  LimitedServoDriver& servos_;
  FrameProcessor& processor_;
  std::vector<StepObserver*> observers_;
  PipelineOptions options_;
  LatestFrameSlot slot_;
  std::atomic<bool> stop_{false};
  // Capture thread only: applies the latest camera settings.
  void ApplyCameraSettings();

  std::mutex camera_mutex_;
  kapfix::v1::CameraSettings camera_settings_;  // the latest, guarded by camera_mutex_
  bool camera_settings_new_ = true;             // not applied yet; guarded by camera_mutex_
  std::mutex servo_mutex_;  // LimitedServoDriver is not thread-safe: control vs watchdog
  // Held while on_health runs, so that two threads' changes are reported in order and the
  // last report is the health as it is. Changes are rare (a device comes or goes).
  mutable std::mutex health_mutex_;
  DevicesHealth health_;
  ServoCommander commander_;             // control thread only
  std::shared_ptr<ServoBelief> belief_;  // options_.servo_belief or the pipeline's own
};

}  // namespace kapfix::agent
