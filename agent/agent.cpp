#include "agent/agent.hpp"

#include <spdlog/spdlog.h>

#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "agent/capture/aravis_frame_source.hpp"
#include "agent/capture/sim_frame_source.hpp"
#include "agent/capture/v4l2_frame_source.hpp"
#include "agent/servo/maestro_servo_driver.hpp"
#include "agent/servo/pca9685_servo_driver.hpp"
#include "agent/servo/sim_servo_driver.hpp"
#include "common/control/controller_factory.hpp"
#include "common/evaluation/closed_loop_evaluation.hpp"

namespace kapfix::agent {
namespace {

// Hardware: one frame of servo latency assumed until calibration measures it.
constexpr int kHardwareActuationDelayFrames = 2;

SimulatedPlatformOptions::Motion ToPlatformMotion(MotionKind kind) {
  return kind == MotionKind::kBoat ? SimulatedPlatformOptions::Motion::kBoat
                                   : SimulatedPlatformOptions::Motion::kKite;
}

std::string ControllerName(ControllerKind kind) { return std::string(ToString(kind)); }

SimulatedPlatformOptions PlatformOptions(const AgentConfig& config) {
  const ClosedLoopOptions base =
      ClosedLoopOptions::ForMotion(ToPlatformMotion(config.simulation.motion));
  SimulatedPlatformOptions o = base.platform;
  o.kite.seed = config.simulation.seed;
  o.kite.gusts = config.simulation.gusts;
  o.boat.seed = config.simulation.seed;
  o.camera.seed = config.simulation.seed;
  o.camera.frame_size = {config.camera.width, config.camera.height};
  o.px_per_deg = 1.0 / config.active_lens().DegPerPxPan();
  o.pan.min_deg = config.servo.pan.limits.min_deg;
  o.pan.max_deg = config.servo.pan.limits.max_deg;
  o.pan.initial_deg = config.servo.pan.limits.park_deg;
  o.tilt.min_deg = config.servo.tilt.limits.min_deg;
  o.tilt.max_deg = config.servo.tilt.limits.max_deg;
  o.tilt.initial_deg = config.servo.tilt.limits.park_deg;
  return o;
}

FixationOptions MakeFixationOptions(const AgentConfig& config) {
  FixationOptions o;
  o.search.axis = config.search.axis;
  o.search.range = config.search.range_px;
  o.search.subpixel = config.search.subpixel;
  o.sampling = config.search.sampling;
  o.channel = config.search.channel;
  o.patch_size = config.search.patch_px;
  o.slice_count = config.search.slices;
  // SSP is not wired into the agent yet: the middle slice.
  o.slice = (config.search.slices + 1) / 2;
  return o;
}

ControllerGains MakeGains(const ControllerConfig& c) {
  ControllerGains g;
  g.p = c.kp;
  g.i = c.ki;
  g.d = c.kd;
  g.dead_band_px = c.dead_band_px;
  g.rate_limit_deg_per_s = c.max_rate_deg_per_s;
  return g;
}

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

}  // namespace

AgentConfig BuiltInConfig(MotionKind motion) {
  AgentConfig config;
  config.simulation.motion = motion;
  config.search.axis = motion == MotionKind::kBoat ? SearchAxis::kY : SearchAxis::kBoth;
  config.controller.kp = 1.0;
  return config;
}

Agent::Agent(AgentConfig config, AgentOptions options)
    : config_(std::move(config)), options_(options) {
  std::string error;
  if (!config_.IsValid(&error)) throw std::runtime_error("invalid configuration: " + error);
  simulated_ = options_.simulate || (config_.camera.backend == CameraBackend::kSim &&
                                     config_.servo.backend == ServoBackend::kSim);
  if (!simulated_ && (config_.camera.backend == CameraBackend::kSim ||
                      config_.servo.backend == ServoBackend::kSim)) {
    throw std::runtime_error(
        "camera and servos must both be \"sim\" or both real hardware (or use --sim)");
  }

  const double fps = config_.camera.fps;
  PipelineOptions pipeline;
  pipeline.frames = options_.frames;
  pipeline.watchdog_ms = config_.watchdog_ms;
  pipeline.default_frame_period_s = 1.0 / fps;
  PredictiveOptions predictive =
      ClosedLoopOptions::ForMotion(ToPlatformMotion(config_.simulation.motion)).predictive;
  MonotonicClockUs clock = SteadyClockNowUs;
  std::unique_ptr<ServoDriver> backend;

  if (simulated_) {
    const std::string& scene_path = config_.simulation.scene;
    const cv::Mat scene = cv::imread(scene_path, cv::IMREAD_COLOR);
    if (scene.empty()) throw std::runtime_error("cannot read scene image '" + scene_path + "'");
    const SimulatedPlatformOptions platform_options = PlatformOptions(config_);
    if (!platform_options.IsValid(&error)) throw std::runtime_error("simulation: " + error);
    platform_ = std::make_shared<SimulatedPlatform>(scene, platform_options);
    if (platform_->upscale_factor() > 1.0) {
      spdlog::info("scene upscaled {:.2f}x to cover the frame and the swing",
                   platform_->upscale_factor());
    }
    auto sim_source = std::make_unique<SimFrameSource>(platform_, fps);
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
  } else {
    source_ = MakeCamera(config_.camera);
    backend = MakeServoBackend(config_.servo);
    pipeline.actuation_delay_frames = kHardwareActuationDelayFrames;
  }
  predictive.predictor.lead_frames = pipeline.actuation_delay_frames;

  servos_ = std::make_unique<LimitedServoDriver>(std::move(backend), config_.servo.pan.limits,
                                                 config_.servo.tilt.limits, clock);
  if (!source_->Open(&error)) throw std::runtime_error(error);
  if (config_.camera.gain_db && !source_->SetGain(*config_.camera.gain_db, &error)) {
    throw std::runtime_error(error);
  }
  if (config_.camera.exposure_us && !source_->SetExposure(*config_.camera.exposure_us, &error)) {
    throw std::runtime_error(error);
  }
  if (!servos_->Open(&error)) throw std::runtime_error(error);

  const LensProfile& lens = config_.active_lens();
  const LensCalibration calibration{lens.DegPerPxPan(), lens.DegPerPxTilt()};
  std::unique_ptr<Controller> controller =
      MakeController(ControllerName(config_.controller.kind), MakeGains(config_.controller),
                     calibration, predictive, &error);
  if (!controller) throw std::runtime_error(error);
  std::shared_ptr<const SearchStrategy> strategy =
      MakeSearchStrategy(config_.search.strategy, &error);
  if (!strategy) throw std::runtime_error(error);
  loop_ = std::make_unique<FixationLoop>(MakeFixationOptions(config_), std::move(strategy),
                                         std::move(controller), calibration);
  processor_ = std::make_unique<FixationProcessor>(*loop_);
  pipeline_ =
      std::make_unique<Pipeline>(*source_, *servos_, *processor_, telemetry_, std::move(pipeline));
}

Agent::~Agent() = default;

PipelineStats Agent::Run() { return pipeline_->Run(); }

void Agent::Stop() { pipeline_->Stop(); }

std::string Agent::Describe() const {
  return source_->Describe() + "; " + servos_->Describe() + "; controller " +
         ControllerName(config_.controller.kind) + ", search " + config_.search.strategy + " " +
         std::string(ToString(config_.search.axis));
}

}  // namespace kapfix::agent
