#include "agent/agent.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <stdexcept>

#include "agent/capture/aravis_frame_source.hpp"
#include "agent/capture/sim_frame_source.hpp"
#include "agent/capture/v4l2_frame_source.hpp"
#include "agent/modes/run_options.hpp"
#include "agent/resume/boot_id.hpp"
#include "agent/resume/stored_settings.hpp"
#include "agent/servo/maestro_servo_driver.hpp"
#include "agent/servo/pca9685_servo_driver.hpp"
#include "agent/servo/sim_servo_driver.hpp"
#include "agent/still_camera/gphoto2_still_camera.hpp"
#include "agent/still_camera/still_camera_trigger.hpp"
#include "common/evaluation/closed_loop_evaluation.hpp"
#include "kapfix/v1/envelope_codec.hpp"
#include "link/curve_key_file.hpp"
#include "link/link_endpoint.hpp"
#include "link/peer_resource_limits.hpp"

namespace kapfix::agent {
namespace {

// Hardware: one frame of servo latency assumed until calibration measures it.
constexpr int kHardwareActuationDelayFrames = 2;
// [jobs] slow jobs waiting at most: calibrations and recordings come one per process (seconds
// apart), the servo driver's reopen one at a time, so a full queue means a disk or a device
// that has stopped. One queue: a reopen may wait behind a disk write (and the other way round).
constexpr std::size_t kWorkerJobs = 16;

// "tcp://*:5555" → "tcp://127.0.0.1:5555": the same port, this machine only.
std::string LoopbackAddress(const std::string& address) {
  if (!address.starts_with("tcp://")) return address;
  const auto colon = address.rfind(':');
  if (colon == std::string::npos || colon < 6) return address;
  return "tcp://127.0.0.1" + address.substr(colon);
}

// The link's CurveZMQ keys, when configured. A fresh install (no station authorised yet)
// serves this machine only: `link` is narrowed to loopback without keys. Throws
// std::runtime_error when the keys cannot be read.
std::optional<kapfix::link::CurveServerKeys> ReadLinkKeys(LinkConfig* link, bool insecure) {
  std::optional<kapfix::link::CurveServerKeys> curve;
  std::string error;
  if (!link->curve_secret_key_file.empty()) {
    // Fresh install (the package's postinst makes the agent's keys and an empty list): no
    // station can be authorised yet, so serve this machine only and say how to add one.
    std::string why;
    const auto stations = kapfix::link::ReadPublicKeyLines(link->curve_authorized_keys_file, &why);
    if (stations && stations->empty()) {
      spdlog::warn(
          "link: no station key in {} yet: serving this machine only (127.0.0.1). To fly from "
          "a station: kapfix-keygen laptop (on the station), append laptop.pub's line to {}, "
          "then systemctl restart kapfix-agent; give the station {}",
          link->curve_authorized_keys_file, link->curve_authorized_keys_file,
          std::filesystem::path(link->curve_secret_key_file).replace_extension(".pub").string());
      link->command_address = LoopbackAddress(link->command_address);
      link->stream_address = LoopbackAddress(link->stream_address);
      link->curve_secret_key_file.clear();
      link->curve_authorized_keys_file.clear();
    }
  }
  if (!link->curve_secret_key_file.empty()) {
    curve = kapfix::link::ReadCurveServerKeys(link->curve_secret_key_file,
                                              link->curve_authorized_keys_file, &error);
    if (!curve) throw std::runtime_error(error);
    spdlog::info("link: CurveZMQ, {} authorised station key(s)", curve->authorized_stations.size());
  }
  if (insecure && link->curve_secret_key_file.empty()) {
    spdlog::warn("--insecure: the link is open to anyone who can reach {} and {}",
                 link->command_address, link->stream_address);
  }
  return curve;
}

// Each link server's connection budget, after raising the open-file limit.
std::size_t ConnectionBudget() {
  // Before binding: descriptors for many connections plus the photos (issue 15, item 3).
  constexpr std::uint64_t kWantedOpenFiles = 65536;
  constexpr std::uint64_t kEnoughOpenFiles = 4096;  // ~100 s of 33 new connections a second
  const std::uint64_t open_files = link::RaiseOpenFileLimit(kWantedOpenFiles);
  if (open_files < kEnoughOpenFiles) {
    spdlog::warn("link: at most {} open files (wanted {}): raise LimitNOFILE", open_files,
                 kWantedOpenFiles);
  }
  link::ReturnLargeBuffersWhenFreed();
  kapfix::v1::QuietLibprotobufLog();  // invalid UTF-8 from a peer: refused, not printed
  // Each server's connection budget: half of the descriptors, less a reserve for photos,
  // calibrations and logs; a connection behind the bounded intake takes three (the peer's,
  // the intake's to the socket, and libzmq's end of that).
  constexpr std::uint64_t kReservedFiles = 256;
  constexpr std::uint64_t kFilesPerConnection = 3;
  return static_cast<std::size_t>(std::clamp<std::uint64_t>(
      (open_files - std::min(open_files, kReservedFiles)) / 2 / kFilesPerConnection, 16, 4096));
}

// One belief per flight: the pipeline tells it what was sent and which frame is processed,
// the fixation controller resolves it (the command in effect when the latency jitters). The
// servos turn at their configured rate (ServoLimits::max_rate_deg_per_s: the rated speed or
// less), so a command is reached over the frames that takes.
std::shared_ptr<ServoBelief> MakeServoBelief(const ServoConfig& servo, double fps, int delay_frames,
                                             int max_delay_frames, ServoTargets play_deg) {
  return std::make_shared<ServoBelief>(
      ServoBeliefOptions{delay_frames, std::max(delay_frames, max_delay_frames),
                         ServoTargets{servo.pan.limits.park_deg, servo.tilt.limits.park_deg},
                         ServoTargets{servo.pan.limits.max_rate_deg_per_s / fps,
                                      servo.tilt.limits.max_rate_deg_per_s / fps},
                         play_deg});
}

}  // namespace

std::unique_ptr<FrameSource> MakeCamera(const CameraConfig& camera) {
  if (camera.backend == CameraBackend::kV4l2) {
    return std::make_unique<V4l2FrameSource>(camera.ToV4l2Options());
  }
  return std::make_unique<AravisFrameSource>(camera.ToAravisOptions());
}

std::unique_ptr<ServoDriver> MakeServoBackend(const ServoConfig& servo) {
  if (servo.backend == ServoBackend::kMaestro) {
    return std::make_unique<MaestroServoDriver>(servo.ToMaestroOptions());
  }
  return std::make_unique<Pca9685ServoDriver>(servo.ToPca9685Options());
}

AgentConfig BuiltInConfig(MotionKind motion) {
  AgentConfig config;
  config.simulation.motion = motion;
  // A boat's view rolls in Y; its X is white jitter a delayed loop cannot cancel, only add to
  // (realistic world, the agent, seeds 1-2: 3.46 / 3.88 px on Y alone, 3.85 / 4.50 on both).
  if (motion == MotionKind::kBoat) config.search.axis = SearchAxis::kY;
  // A simulated flight from a user's shell: photos next to it, not in the service's folder.
  config.photos.dir = "kapfix-photos";
  config.state_dir = "kapfix-state";
  return config;
}

bool CheckLinkExposure(const LinkConfig& link, bool insecure, std::string* error) {
  for (const std::string& address : {link.command_address, link.stream_address}) {
    // Parsed as the servers parse it: exactly one endpoint, judged on its literal address.
    const std::optional<link::LinkEndpoint> endpoint = link::ParseLinkEndpoint(address, error);
    if (!endpoint) return false;
    if (!endpoint->loopback && link.curve_secret_key_file.empty() && !insecure) {
      if (error) {
        *error = "link address " + address +
                 " is reachable from the network but no CurveZMQ keys are configured "
                 "(link.curve_secret_key_file): bind to 127.0.0.1, configure keys, or pass "
                 "--insecure";
      }
      return false;
    }
  }
  return true;
}

// The agent's wiring, in construction order.
Agent::Agent(AgentConfig config, AgentOptions options)
    : config_(std::move(config)), options_(options) {
  std::string error;
  if (!config_.IsValid(&error)) throw std::runtime_error("invalid configuration: " + error);
  if (!CheckLinkExposure(config_.link, options_.insecure, &error)) {
    throw std::runtime_error(error);
  }
  // Issue 14: a new session id, and what the previous run left (its settings from here on).
  boot_id_ = DrawBootId();
  resume_store_ =
      std::make_unique<ResumeStore>(std::filesystem::path(config_.state_dir) / "resume");
  std::optional<ResumeRecord> resumed;
  if (options_.resume && config_.resume) resumed = LoadResumeRecord(*resume_store_, &config_);
  const std::optional<kapfix::link::CurveServerKeys> curve =
      ReadLinkKeys(&config_.link, options_.insecure);
  simulated_ = options_.simulate || (config_.camera.backend == CameraBackend::kSim &&
                                     config_.servo.backend == ServoBackend::kSim);
  if (!simulated_ && (config_.camera.backend == CameraBackend::kSim ||
                      config_.servo.backend == ServoBackend::kSim)) {
    throw std::runtime_error(
        "camera and servos must both be \"sim\" or both real hardware (or use --sim)");
  }

  PredictiveOptions predictive;
  PipelineOptions pipeline = OpenDevices(&predictive);
  const std::size_t budget = ConnectionBudget();
  StartPublisher(curve, budget);
  StartPhotos();
  video_ = std::make_unique<VideoDownlink>(*publisher_, config_.video);
  telemetry_publisher_ = std::make_unique<TelemetryPublisher>(
      *publisher_, [video = video_.get()] { return video->dropped(); });
  // Stored calibrations replace the profiles' nominal deg/px (after the simulation took its
  // truth from the nominal one: the simulated lens does not change).
  calibrations_ =
      std::make_unique<CalibrationStore>(std::filesystem::path(config_.state_dir) / "calibration");
  for (LensProfile& lens : config_.lenses) {
    std::string why;
    if (const auto stored = calibrations_->Load(lens.name, &why)) {
      lens.ApplyCalibration(*stored);
      spdlog::info("lens {}: stored calibration {:.5f} / {:.5f} deg/px", lens.name,
                   stored->pan_deg_per_px, stored->tilt_deg_per_px);
    } else if (!why.empty()) {
      spdlog::warn("lens {}: stored calibration ignored: {}", lens.name, why);
    }
  }
  PhotoStore* store = photo_store_.get();
  state_ = std::make_unique<StateKeeper>(
      config_, *publisher_, simulated_, [store] { return store->count(); }, calibrations_.get());
  state_republisher_ = std::make_unique<StateRepublisher>(*state_);
  worker_ = std::make_shared<WorkQueue>("worker", kWorkerJobs);
  state_->StoreCalibrationsOn(worker_.get());
  pipeline.worker = worker_;  // the servo driver's reopen

  StartModes(resumed, pipeline, predictive);
  std::vector<StepObserver*> observers{telemetry_publisher_.get(), video_.get(), photos_.get()};
  if (options_.keep_telemetry) observers.push_back(&telemetry_);
  // The devices' health, kept by the pipeline, goes to systemctl status and the AgentState.
  pipeline.on_health = [notifier = notifier_.get(),
                        state = state_.get()](const DevicesHealth& health) {
    notifier->Status(StatusLine(health));
    state->OnDeviceHealth(health);
  };
  pipeline_ = std::make_unique<Pipeline>(*source_, *servos_, *modes_, std::move(observers),
                                         std::move(pipeline));
  state_->OnDeviceHealth(pipeline_->health());  // as it is at start

  StartCommandServer(curve, budget);
}

PipelineOptions Agent::OpenDevices(PredictiveOptions* predictive_out) {
  std::string error;
  const double fps = config_.camera.fps;
  PipelineOptions pipeline;
  pipeline.frames = options_.frames;
  pipeline.watchdog_ms = config_.watchdog_ms;
  pipeline.default_frame_period_s = 1.0 / fps;
  PredictiveOptions predictive =
      ClosedLoopOptions::ForMotion(ToPlatformMotion(config_.simulation.motion)).predictive;
  MonotonicClockUs clock = SteadyClockNowUs;
  std::unique_ptr<ServoDriver> backend;
  int max_delay_frames = 0;  // [frames] the longest actuation delay (latency jitter); 0: fixed
  // [deg] the servos' play: the simulated ones' own, as their latency is; on hardware the
  // configured servo.*.play_deg (not yet estimated while flying).
  ServoTargets servo_play{0, 0};

  if (simulated_) {
    const std::string& scene_path = config_.simulation.scene;
    const cv::Mat scene = cv::imread(scene_path, cv::IMREAD_COLOR);
    if (scene.empty()) throw std::runtime_error("cannot read scene image '" + scene_path + "'");
    const SimulatedPlatformOptions platform_options = MakePlatformOptions(config_);
    if (!platform_options.IsValid(&error)) throw std::runtime_error("simulation: " + error);
    platform_ = std::make_shared<SimulatedPlatform>(scene, platform_options);
    if (const std::optional<std::string> note = SimulatedWorldScaleNote(config_)) {
      spdlog::warn("simulation: {}", *note);
    }
    if (platform_->upscale_factor() > 1.0) {
      spdlog::info("scene upscaled {:.2f}x to cover the frame and the swing",
                   platform_->upscale_factor());
    }
    auto sim_source = std::make_unique<SimFrameSource>(platform_, fps, options_.real_time);
    const SimFrameSource* truth = sim_source.get();
    pipeline.view_offset = [truth](std::uint64_t index) { return truth->ViewOffset(index); };
    source_ = std::move(sim_source);
    backend = std::make_unique<SimServoDriver>(platform_);
    // Simulated time: the rate limit counts frames, not the host's speed.
    std::shared_ptr<SimulatedPlatform> platform = platform_;
    clock = [platform, fps] {
      return static_cast<std::int64_t>(std::llround(platform->frame() * 1e6 / fps));
    };
    pipeline.lock_step = true;
    pipeline.actuation_delay_frames = 1 + platform_options.pan.latency_frames;
    max_delay_frames =
        1 + std::max(platform_options.pan.latency_frames, platform_options.pan.latency_max_frames);
    servo_play = {platform_options.pan.backlash_deg, platform_options.tilt.backlash_deg};
  } else {
    source_ = MakeCamera(config_.camera);
    backend = MakeServoBackend(config_.servo);
    pipeline.actuation_delay_frames = kHardwareActuationDelayFrames;
    servo_play = {config_.servo.pan.play_deg, config_.servo.tilt.play_deg};
  }
  predictive.predictor.lead_frames = pipeline.actuation_delay_frames;
  // With a jittering latency, aimed at every delay it may take (as the evaluation does).
  predictive.lead_jitter_frames = std::max(0, max_delay_frames - pipeline.actuation_delay_frames);
  pipeline.servo_belief = MakeServoBelief(config_.servo, fps, pipeline.actuation_delay_frames,
                                          max_delay_frames, servo_play);

  servos_ = std::make_unique<LimitedServoDriver>(std::move(backend), config_.servo.pan.limits,
                                                 config_.servo.tilt.limits, clock, 1.0 / fps);
  // Start-up waits for hardware: a device that is not there yet is said once and retried
  // with back-off by the pipeline, rather than ending the agent (issue 10).
  pipeline.camera_settings = config_.camera.settings;  // applied by the pipeline once open
  if (!source_->Open(&error)) {
    pipeline.camera_open = false;
    pipeline.camera_error = error;
    spdlog::warn("camera: {}", error);
  }
  if (!servos_->Open(&error)) {
    pipeline.servos_open = false;
    pipeline.servos_error = error;
    spdlog::warn("servos: {}", error);
  }
  if (simulated_) pipeline.park_wait = [] {};  // simulated time: no wall-clock wait
  notifier_ = std::make_unique<SystemdNotifier>();
  pipeline.on_alive = [notifier = notifier_.get()] { notifier->Alive(); };

  *predictive_out = predictive;
  return pipeline;
}

void Agent::StartPublisher(const std::optional<kapfix::link::CurveServerKeys>& curve,
                           std::size_t budget) {
  StreamPublisherOptions publisher_options;
  publisher_options.max_connections = budget;
  publisher_options.bind_endpoint = config_.link.stream_address;
  publisher_options.agent_id = config_.agent_id;
  publisher_options.boot_id = boot_id_;
  publisher_options.heartbeat_interval = std::chrono::milliseconds(config_.link.heartbeat_ms);
  publisher_options.curve = curve;
  publisher_ = std::make_unique<StreamPublisher>(publisher_options);
  // The log lines go to the station too; removed again in ~Agent, before the publisher goes.
  log_publisher_ = std::make_shared<LogPublisher>(*publisher_);
  spdlog::default_logger()->sinks().push_back(log_publisher_);
}

void Agent::StartPhotos() {
  photo_store_ = std::make_unique<PhotoStore>(config_.photos.dir);
  photos_ = std::make_unique<PhotoTaker>(*photo_store_, *publisher_, [this] {
    return state_->settings()->lens;  // photos are taken once the agent runs
  });
  photos_->SetSettings(config_.photo);
  // The still camera is opened at its first photo, so it costs nothing until selected.
  photos_->SetStillCamera(std::make_shared<StillCameraTrigger>(
      std::make_unique<Gphoto2StillCamera>(), options_.still_camera_delete));
  photos_->SetCamera(options_.photo_camera);
}

void Agent::StartModes(const std::optional<ResumeRecord>& resumed, const PipelineOptions& pipeline,
                       const PredictiveOptions& predictive) {
  const double fps = config_.camera.fps;
  ModeRunnerOptions modes;
  modes.start_mode = options_.start_mode;
  modes.default_deadline = {config_.search.swing_frames, config_.search.swing_seconds};
  modes.predictive = predictive;
  modes.actuation_delay_frames = pipeline.actuation_delay_frames;
  modes.servo_belief = pipeline.servo_belief;
  modes.frame_period_s = 1.0 / fps;
  modes.recordings_dir = (std::filesystem::path(config_.photos.dir) / "free-swing").string();
  modes.worker = worker_;
  resume_recorder_ = std::make_unique<ResumeRecorder>(
      *resume_store_, *state_, resumed.value_or(ResumeRecord{}), config_.lens);
  // A resumed fixation first finds its stored view again; any other stored mode is taken up
  // as it was (follow) or as idle (a process cut short by the restart).
  const bool resume_view =
      resumed && resumed->mode == AgentMode::kFixate && !resumed->reference_frame.empty();
  if (resumed && !resume_view) {
    modes.start_mode = resumed->mode == AgentMode::kFollow ? AgentMode::kFollow : AgentMode::kIdle;
  }
  modes_ = std::make_unique<ModeRunner>(state_->settings(), modes, *resume_recorder_);
  if (resume_view) modes_->RequestResume(resumed->reference_frame, resumed->slice);
  if (resumed && !resume_view) state_->OnResumeEnded(true);
}

void Agent::StartCommandServer(const std::optional<kapfix::link::CurveServerKeys>& curve,
                               std::size_t budget) {
  Pipeline* running = pipeline_.get();
  executor_ = std::make_unique<CommandExecutor>(CommandTargets{
      .state = *state_,
      .modes = *modes_,
      .photos = *photos_,
      .video = *video_,
      .apply_camera =
          [running](const kapfix::v1::CameraSettings& camera) {
            running->SetCameraSettings(camera);
          },
      .free_swing_recording_possible = true,
  });
  CommandServerOptions server_options;
  server_options.bind_endpoint = config_.link.command_address;
  server_options.agent_id = config_.agent_id;
  server_options.boot_id = boot_id_;
  server_options.curve = curve;
  server_options.max_connections = budget;
  server_options.replay->state_file = std::filesystem::path(config_.state_dir) / "replay_horizon";
  server_options.rate_limit = CommandRateLimitOptions{
      .station_per_s = config_.link.command_rate_per_s,
      .station_burst = config_.link.command_burst,
      .all_per_s = config_.link.all_commands_rate_per_s,
      .all_burst = 2 * config_.link.all_commands_rate_per_s,
  };
  recording_control_ = std::make_unique<RecordingControl>(*executor_, *resume_recorder_);
  server_ = std::make_unique<CommandServer>(*recording_control_, server_options);
  stream_endpoint_ = publisher_->Start();
  command_endpoint_ = server_->Start();
  notifier_->Ready("commands on " + command_endpoint_ + "; " + StatusLine(pipeline_->health()));
}

Agent::~Agent() {
  // The command server first: no command may reach parts that are going away.
  if (server_) server_->Stop();
  if (log_publisher_) {
    auto& sinks = spdlog::default_logger()->sinks();
    sinks.erase(std::remove(sinks.begin(), sinks.end(), log_publisher_), sinks.end());
  }
}

PipelineStats Agent::Run() {
  state_->PublishState();
  return pipeline_->Run();
}

void Agent::Stop() {
  notifier_->Stopping();
  pipeline_->Stop();
}

std::string Agent::Describe() const {
  const auto settings = state_->settings();
  return source_->Describe() + "; " + servos_->Describe() + "; controller " +
         kapfix::v1::WordOf(settings->gains.controller()) + ", search " +
         settings->search.strategy + " " + std::string(ToString(settings->search.axis)) +
         "; commands on " + command_endpoint_ + ", streams on " + stream_endpoint_;
}

}  // namespace kapfix::agent
