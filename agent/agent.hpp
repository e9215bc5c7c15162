#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "agent/capture/frame_source.hpp"
#include "agent/config/agent_config.hpp"
#include "agent/pipeline/pipeline.hpp"
#include "agent/pipeline/telemetry_recorder.hpp"
#include "agent/servo/limited_servo_driver.hpp"
#include "common/fixation/fixation_loop.hpp"
#include "common/sim/simulated_platform.hpp"

namespace kapfix::agent {

struct AgentOptions {
  // Camera and servos in simulation (SimFrameSource, SimServoDriver over one
  // SimulatedPlatform), whatever the config's backends say (--sim). Also used when both
  // backends are "sim".
  bool simulate = false;
  std::uint64_t frames = 0;  // frames to process; 0 = until Stop()
};

// kapfix-agent's built-in configuration (no --config): AgentConfig's defaults — everything
// in simulation — with EvaluateClosedLoop's choices for the closed loop
// (common/evaluation/closed_loop_evaluation.hpp): a kite is searched on both axes so the tilt
// servo holds its Y jitter, a boat along Y, and the controller's gain is 1 (the config
// default kp 0.8 leaves 5.2 px RMS on the kite flight of 900 frames where 1.0 leaves 2.9).
AgentConfig BuiltInConfig(MotionKind motion);

// The agent's top object: wires the parts from an AgentConfig — camera and servos (real or
// simulated), LimitedServoDriver in front of the servos, the fixation loop (search strategy,
// controller, lens calibration) and the pipeline's threads — and runs them. It decides
// nothing itself; the parts do.
//
// Simulation (SPEC §3) follows EvaluateClosedLoop's choices: SPEC §3's swing on the scene
// with gusts as configured, servos with one frame of latency, the lens's deg/px as the
// simulated px/deg and as an exact calibration, the predictive controller's lead =
// 1 + the servos' latency, and lock-step threads (PipelineOptions::lock_step) on simulated
// time — LimitedServoDriver's rate limit runs on the simulated clock too — so a flight is
// deterministic. Hardware runs free on the wall clock.
class Agent {
 public:
  // Opens camera and servos. Throws std::runtime_error with a one-line reason (an unreadable
  // scene, a device that does not open, an invalid config).
  Agent(AgentConfig config, AgentOptions options);
  ~Agent();
  Agent(const Agent&) = delete;
  Agent& operator=(const Agent&) = delete;

  // Flies until options.frames are processed or Stop(); parks the servos at the end.
  PipelineStats Run();
  void Stop();

  bool simulated() const { return simulated_; }
  const AgentConfig& config() const { return config_; }
  const TelemetryRecorder& telemetry() const { return telemetry_; }
  std::string Describe() const;  // camera, servos, controller on one line
  // Servo hard limits in force (from the config).
  const ServoLimits& limits(ServoAxis axis) const { return servos_->limits(axis); }

 private:
  AgentConfig config_;
  AgentOptions options_;
  bool simulated_ = false;
  std::shared_ptr<SimulatedPlatform> platform_;
  std::unique_ptr<FrameSource> source_;
  std::unique_ptr<LimitedServoDriver> servos_;
  std::unique_ptr<FixationLoop> loop_;
  std::unique_ptr<FixationProcessor> processor_;
  TelemetryRecorder telemetry_;
  std::unique_ptr<Pipeline> pipeline_;
};

}  // namespace kapfix::agent
