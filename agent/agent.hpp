#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>

#include "agent/capture/frame_source.hpp"
#include "agent/commands/calibration_store.hpp"
#include "agent/commands/command_executor.hpp"
#include "agent/commands/state_keeper.hpp"
#include "agent/commands/state_republisher.hpp"
#include "agent/config/agent_config.hpp"
#include "agent/downlink/log_publisher.hpp"
#include "agent/downlink/telemetry_publisher.hpp"
#include "agent/downlink/video_downlink.hpp"
#include "agent/modes/mode_runner.hpp"
#include "agent/photos/photo_store.hpp"
#include "agent/photos/photo_taker.hpp"
#include "agent/pipeline/pipeline.hpp"
#include "agent/pipeline/telemetry_recorder.hpp"
#include "agent/resume/recording_control.hpp"
#include "agent/resume/resume_record.hpp"
#include "agent/resume/resume_recorder.hpp"
#include "agent/resume/resume_store.hpp"
#include "agent/server/command_server.hpp"
#include "agent/server/stream_publisher.hpp"
#include "agent/service/systemd_notifier.hpp"
#include "agent/servo/limited_servo_driver.hpp"
#include "agent/worker/work_queue.hpp"
#include "common/sim/simulated_platform.hpp"
#include "link/curve_server_keys.hpp"

namespace kapfix::agent {

struct AgentOptions {
  // Camera and servos in simulation (SimFrameSource, SimServoDriver over one
  // SimulatedPlatform), whatever the config's backends say (--sim). Also used when both
  // backends are "sim".
  bool simulate = false;
  // Simulation: frames come at the camera's rate on the wall clock, as from a real camera.
  // Off: as fast as the machine allows (benchmarks, tests).
  bool real_time = true;
  std::uint64_t frames = 0;  // frames to process; 0 = until Stop()
  AgentMode start_mode = AgentMode::kFixate;
  // Keep every step's telemetry in memory for the flight report (--report): memory grows
  // with the flight, so only for bounded runs.
  bool keep_telemetry = false;
  // Allow the link to listen beyond this machine without CurveZMQ keys (logged as a warning).
  bool insecure = false;
  // The camera photos are taken with (--photo-camera); UNSPECIFIED keeps the configured one.
  kapfix::v1::PhotoCamera photo_camera = kapfix::v1::PHOTO_CAMERA_UNSPECIFIED;
  // Delete each still-camera photo on the camera once it is stored on the agent.
  bool still_camera_delete = false;
  // Come back as the previous run left (config key `resume` too; --no-resume): issue 14.
  bool resume = true;
};

// kapfix-agent's built-in configuration (no --config): AgentConfig's defaults — everything
// in simulation — with EvaluateClosedLoop's choices for the closed loop
// (common/evaluation/closed_loop_evaluation.hpp): a kite is searched on both axes so the tilt
// servo holds its Y jitter, a boat along Y, and the controller's gain is 1 (the config
// default P gain 0.8 leaves 5.2 px RMS on the kite flight of 900 frames where 1.0 leaves 2.9).
AgentConfig BuiltInConfig(MotionKind motion);

// The real camera and servo backend a config names (not "sim"); not opened.
std::unique_ptr<FrameSource> MakeCamera(const CameraConfig& camera);
std::unique_ptr<ServoDriver> MakeServoBackend(const ServoConfig& servo);

// Without CurveZMQ keys the link may only listen on this machine (loopback, ipc, inproc)
// unless `insecure`; false with the reason otherwise (issue 5).
bool CheckLinkExposure(const LinkConfig& link, bool insecure, std::string* error);

// The agent's top object: wires the parts from an AgentConfig and runs them. It decides
// nothing itself; the parts do.
// - camera and servos, real or simulated, with LimitedServoDriver in front of the servos;
// - the modes (ModeRunner) on the control thread of the Pipeline;
// - the link: StreamPublisher (telemetry, video, reports, photos, state) and CommandServer
//   with the CommandExecutor behind it;
// - the step observers: TelemetryPublisher, VideoDownlink, PhotoTaker and, for a report,
//   TelemetryRecorder.
//
// Simulation (SPEC §3) follows EvaluateClosedLoop's choices: SPEC §3's swing on the scene
// with gusts as configured, servos with one frame of latency, the lens's deg/px as the
// simulated px/deg and as an exact calibration, the predictive controller's lead =
// 1 + the servos' latency, and lock-step threads (PipelineOptions::lock_step) on simulated
// time — LimitedServoDriver's rate limit runs on the simulated clock too — so a flight is
// deterministic. Hardware runs free on the wall clock.
class Agent {
 public:
  // Opens camera, servos and the link's sockets. A camera or servo driver that does not open
  // is logged and waited for (the pipeline retries it with back-off). Throws
  // std::runtime_error with a one-line reason for what waiting cannot fix (an unreadable
  // scene, an invalid config, unreadable keys, an address already in use).
  Agent(AgentConfig config, AgentOptions options);
  ~Agent();
  Agent(const Agent&) = delete;
  Agent& operator=(const Agent&) = delete;

  // Flies until options.frames are processed or Stop(); parks the servos at the end.
  PipelineStats Run();
  void Stop();

  bool simulated() const { return simulated_; }
  // [deg/px] simulation only: the simulated lens's true degrees per pixel (both axes), what
  // the flight report compares the online estimate with; none on hardware.
  std::optional<double> true_deg_per_px() const {
    if (!platform_) return std::nullopt;
    return 1.0 / platform_->options().px_per_deg;
  }
  const TelemetryRecorder& telemetry() const { return telemetry_; }
  std::string Describe() const;  // camera, servos, controller, link on one line
  // Servo hard limits in force (from the config).
  const ServoLimits& limits(ServoAxis axis) const { return servos_->limits(axis); }
  const std::string& command_endpoint() const { return command_endpoint_; }
  const std::string& stream_endpoint() const { return stream_endpoint_; }
  StreamPublisher::Counters link_counters() const { return publisher_->counters(); }
  std::uint64_t video_frames_sent() const { return video_->sent(); }
  PhotoTaker& photos() { return *photos_; }
  // Header.boot_id of everything this agent sends: drawn once per start (issue 14).
  std::uint64_t boot_id() const { return boot_id_; }
  // Waits until the resume record holds every change so far (it is written on change, on a
  // thread of its own, and at the end).
  void FlushResumeRecord() { resume_recorder_->Flush(); }

 private:
  // The parts of the wiring, in the order Agent::Agent calls them.
  // Camera and servos (real or simulated), opened or left for the pipeline to retry; the
  // pipeline's options for them, and the predictive controller's options in `predictive`.
  PipelineOptions OpenDevices(PredictiveOptions* predictive);
  void StartPublisher(const std::optional<kapfix::link::CurveServerKeys>& curve,
                      std::size_t budget);
  void StartPhotos();
  // The modes, as the previous run left them when `resumed`.
  void StartModes(const std::optional<ResumeRecord>& resumed, const PipelineOptions& pipeline,
                  const PredictiveOptions& predictive);
  void StartCommandServer(const std::optional<kapfix::link::CurveServerKeys>& curve,
                          std::size_t budget);

  // The configuration as started: wiring reads its devices, link and folders. The settings
  // are StateKeeper's (state_->settings()); nothing reads them here after construction.
  AgentConfig config_;
  AgentOptions options_;
  bool simulated_ = false;
  std::shared_ptr<SimulatedPlatform> platform_;
  std::unique_ptr<FrameSource> source_;
  std::unique_ptr<LimitedServoDriver> servos_;
  std::unique_ptr<SystemdNotifier> notifier_;
  // The link and the observers outlive the pipeline and the command server that use them
  // (members are destroyed in reverse order).
  std::unique_ptr<StreamPublisher> publisher_;
  std::shared_ptr<LogPublisher> log_publisher_;
  std::unique_ptr<PhotoStore> photo_store_;
  std::unique_ptr<PhotoTaker> photos_;
  std::unique_ptr<VideoDownlink> video_;
  std::unique_ptr<TelemetryPublisher> telemetry_publisher_;
  TelemetryRecorder telemetry_;
  std::unique_ptr<CalibrationStore> calibrations_;
  // Slow work off the control thread (calibrations, free-swing recordings, the servo driver's
  // reopen); after what its jobs use, before the state, modes and pipeline that post to it.
  std::shared_ptr<WorkQueue> worker_;
  std::unique_ptr<StateKeeper> state_;
  std::unique_ptr<StateRepublisher> state_republisher_;
  std::unique_ptr<ResumeStore> resume_store_;
  std::unique_ptr<ResumeRecorder> resume_recorder_;  // in front of state_, behind modes_
  std::unique_ptr<ModeRunner> modes_;
  std::unique_ptr<Pipeline> pipeline_;
  std::unique_ptr<CommandExecutor> executor_;
  std::unique_ptr<RecordingControl> recording_control_;  // in front of executor_
  std::unique_ptr<CommandServer> server_;
  std::string command_endpoint_;
  std::string stream_endpoint_;
  std::uint64_t boot_id_ = 0;
};

}  // namespace kapfix::agent
