#include "agent/pipeline/pipeline.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <thread>

namespace kapfix::agent {
namespace {

double MsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
      .count();
}

}  // namespace

Pipeline::Pipeline(FrameSource& source, LimitedServoDriver& servos, FrameProcessor& processor,
                   std::vector<StepObserver*> observers, PipelineOptions options)
    : source_(source),
      servos_(servos),
      processor_(processor),
      observers_(std::move(observers)),
      options_(std::move(options)),
      commander_(servos_, servo_mutex_,
                 ServoCommanderOptions{
                     .retry_initial_ms = options_.retry_initial_ms,
                     .retry_max_ms = options_.retry_max_ms,
                     .worker = options_.worker ? options_.worker
                                               : std::make_shared<WorkQueue>("servo reopener", 1),
                     .on_health = [this](const DeviceHealth& health) { SetServoHealth(health); },
                 }) {
  camera_settings_ = options_.camera_settings;
  belief_ = options_.servo_belief;
  if (!belief_) {
    // A fixed latency: the command sent actuation_delay_frames earlier, park before the first.
    belief_ = std::make_shared<ServoBelief>(
        ServoBeliefOptions{options_.actuation_delay_frames, options_.actuation_delay_frames,
                           ServoTargets{servos_.limits(ServoAxis::kPan).park_deg,
                                        servos_.limits(ServoAxis::kTilt).park_deg}});
  }
  if (!options_.camera_open) health_.camera = DeviceHealth::Waiting(options_.camera_error);
  if (!options_.servos_open) {
    health_.servos = DeviceHealth::Waiting(options_.servos_error);
    commander_.StartOut(options_.servos_error);
  }
}

DevicesHealth Pipeline::health() const {
  std::lock_guard lock(health_mutex_);
  return health_;
}

void Pipeline::SetCameraHealth(DeviceHealth health) {
  std::lock_guard lock(health_mutex_);
  if (health_.camera == health) return;
  health_.camera = std::move(health);
  if (options_.on_health) options_.on_health(health_);
}

void Pipeline::SetServoHealth(DeviceHealth health) {
  std::lock_guard lock(health_mutex_);
  if (health_.servos == health) return;
  health_.servos = std::move(health);
  if (options_.on_health) options_.on_health(health_);
}

PipelineStats Pipeline::Run() {
  PipelineStats stats;
  const auto start = std::chrono::steady_clock::now();
  Watchdog watchdog(
      std::chrono::milliseconds(options_.watchdog_ms),
      [this] {
        std::lock_guard lock(servo_mutex_);
        spdlog::warn("control loop stalled for {} ms: parking the servos", options_.watchdog_ms);
        std::string error;
        if (!servos_.Park(&error)) spdlog::error("watchdog could not park the servos: {}", error);
      },
      options_.watchdog_clock);
  std::uint64_t grab_errors = 0;
  std::string capture_error;
  std::uint64_t reconnects = 0;
  std::thread capture([this, &grab_errors, &capture_error, &reconnects, &watchdog] {
    PipelineStats capture_stats;
    CaptureThread(&capture_stats, [&watchdog] { watchdog.Disarm(); });
    grab_errors = capture_stats.grab_errors;
    capture_error = capture_stats.error;
    reconnects = capture_stats.camera_reconnects;
  });
  ControlThread(&stats, [&watchdog] { watchdog.Kick(); });
  stats.wall_s = MsSince(start) / 1000.0;
  stop_ = true;
  slot_.Close();
  capture.join();
  watchdog.Stop();
  stats.watchdog_stalls = watchdog.stall_count();
  stats.dropped = slot_.dropped();
  stats.grab_errors = grab_errors;
  stats.camera_reconnects = reconnects;
  if (stats.error.empty()) stats.error = capture_error;
  std::string error;
  std::lock_guard lock(servo_mutex_);
  if (!servos_.placed()) return stats;  // never moved: nothing to park
  const double period_s = options_.default_frame_period_s;
  const std::function<void()> wait = options_.park_wait ? options_.park_wait : [period_s] {
    std::this_thread::sleep_for(std::chrono::duration<double>(period_s));
  };
  if (servos_.ParkAndWait(wait, &error)) {
    spdlog::info("servos parked");
  } else {
    spdlog::warn("could not park the servos at the end: {}", error);
  }
  return stats;
}

void Pipeline::SetCameraSettings(const kapfix::v1::CameraSettings& settings) {
  std::lock_guard lock(camera_mutex_);
  camera_settings_ = settings;
  camera_settings_new_ = true;
}

void Pipeline::ApplyCameraSettings() {
  kapfix::v1::CameraSettings settings;
  {
    std::lock_guard lock(camera_mutex_);
    settings = camera_settings_;
    camera_settings_new_ = false;
  }
  std::string error;
  // A refused setting leaves the camera's own value and the flight goes on: a warning.
  if (!source_.Apply(settings, &error)) {
    spdlog::warn("camera settings not all applied (the camera keeps its own value): {}", error);
  }
}

bool Pipeline::Reconnect(const std::string& reason, bool at_start) {
  SetCameraHealth(at_start ? DeviceHealth::Waiting(reason) : DeviceHealth::Lost(reason));
  if (at_start) {
    spdlog::warn(
        "camera not there: {}; waiting for it (retrying with back-off, the servos are "
        "not moved until it delivers a frame)",
        reason);
  } else {
    spdlog::error("camera lost: {}; the servos hold, reconnecting", reason);
  }
  const auto lost = std::chrono::steady_clock::now();
  int wait_ms = options_.retry_initial_ms;
  for (int attempt = 1; !stop_; ++attempt) {
    // Sleep in short steps so that Stop() is not held up by a long back-off.
    const auto until = std::chrono::steady_clock::now() + std::chrono::milliseconds(wait_ms);
    while (!stop_ && std::chrono::steady_clock::now() < until) {
      if (options_.on_alive) options_.on_alive();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (stop_) break;
    std::string error;
    if (source_.Open(&error)) {
      ApplyCameraSettings();  // the latest ones: a reopened camera may have forgotten them
      spdlog::info("camera back after {:.1f} s ({} attempts): {}", MsSince(lost) / 1000.0, attempt,
                   source_.Describe());
      SetCameraHealth(DeviceHealth::Ok());
      return true;
    }
    spdlog::warn("camera reconnect attempt {} failed: {}; next in {} ms", attempt, error,
                 std::min(2 * wait_ms, options_.retry_max_ms));
    wait_ms = std::min(2 * wait_ms, options_.retry_max_ms);
  }
  return false;
}

void Pipeline::CaptureThread(PipelineStats* stats, const std::function<void()>& on_outage) {
  // A reopened camera numbers its frames from 0 again; the flight's numbering must go on.
  std::uint64_t index_base = 0;
  std::optional<std::uint64_t> last_index;
  if (!options_.camera_open) {
    std::string error;
    if (source_.Open(&error)) {
      SetCameraHealth(DeviceHealth::Ok());
    } else if (!Reconnect(error, true)) {
      slot_.Close();
      return;
    }
  }
  while (!stop_) {
    bool settings_new = false;
    {
      std::lock_guard lock(camera_mutex_);
      settings_new = camera_settings_new_;
    }
    if (settings_new) ApplyCameraSettings();
    CapturedFrame frame;
    std::string error;
    if (!source_.Grab(&frame, &error)) {
      ++stats->grab_errors;
      if (!options_.reconnect_camera) {
        SetCameraHealth(DeviceHealth::Lost(error));
        stats->error = error;
        spdlog::error("capture: {}", error);
        break;
      }
      on_outage();
      if (!Reconnect(error, false)) break;
      ++stats->camera_reconnects;
      if (last_index) index_base = *last_index + 1;
      continue;
    }
    frame.index += index_base;
    last_index = frame.index;
    const std::uint64_t index = frame.index;
    slot_.Put(std::move(frame));
    if (options_.lock_step && !slot_.WaitDone(index)) break;
  }
  slot_.Close();
}

void Pipeline::ControlThread(PipelineStats* stats, const std::function<void()>& kick) {
  std::optional<std::int64_t> previous_time_us;
  while (auto frame = slot_.Take()) {
    const auto start = std::chrono::steady_clock::now();
    double dt_s = options_.default_frame_period_s;
    if (previous_time_us && frame->capture_time_us > *previous_time_us) {
      dt_s = static_cast<double>(frame->capture_time_us - *previous_time_us) * 1e-6;
    }
    previous_time_us = frame->capture_time_us;

    const ServoTargets current = belief_->Expose(static_cast<std::int64_t>(frame->index));
    const FrameOutcome outcome = processor_.Process(*frame, current, dt_s);
    const FixationLoop::Step& step = outcome.step;
    const ServoTargets angles = commander_.Command(step.targets);
    const ServoCommander::Counters servo = commander_.counters();
    stats->servo_errors = servo.errors;
    stats->servo_outages = servo.outages;
    stats->servo_recoveries = servo.recoveries;
    belief_->Sent(static_cast<std::int64_t>(frame->index), angles);

    TelemetryRecord record;
    record.index = frame->index;
    record.capture_time_us = frame->capture_time_us;
    record.found = step.match.found;
    record.displacement_x_px = step.match.displacement.x;
    record.displacement_y_px = step.match.displacement.y;
    record.confidence = step.match.confidence;
    record.lock_lost = step.lock_lost;
    record.off_target = step.off_target;
    record.target_pan_deg = step.targets.pan_deg;
    record.target_tilt_deg = step.targets.tilt_deg;
    record.angle_pan_deg = angles.pan_deg;
    record.angle_tilt_deg = angles.tilt_deg;
    record.loop_latency_ms = MsSince(start);
    record.mode = outcome.mode;
    record.slice = outcome.slice;
    record.distance = step.match.distance;
    record.reference_frame = outcome.reference_frame;
    record.reference_seen_at = outcome.reference_seen_at;
    record.estimate = step.estimate;
    const DevicesHealth devices = health();
    record.camera_health = devices.camera;
    record.servo_health = devices.servos;
    if (options_.view_offset) {
      if (const auto offset = options_.view_offset(frame->index)) {
        record.view_offset_x_px = offset->x;
        record.view_offset_y_px = offset->y;
      }
    }
    for (StepObserver* observer : observers_) observer->OnStep(*frame, outcome, record);
    kick();
    if (options_.on_alive) options_.on_alive();
    ++stats->processed;
    slot_.MarkDone(frame->index);
    if (options_.frames > 0 && stats->processed >= options_.frames) break;
    if (stop_) break;
  }
  stop_ = true;
  slot_.Close();
}

}  // namespace kapfix::agent
