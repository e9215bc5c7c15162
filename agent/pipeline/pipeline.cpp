#include "agent/pipeline/pipeline.hpp"

#include <spdlog/spdlog.h>

#include <chrono>
#include <thread>

#include "agent/pipeline/watchdog.hpp"

namespace kapfix::agent {
namespace {

constexpr std::size_t kCommandHistory = 64;

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
      options_(std::move(options)) {}

PipelineStats Pipeline::Run() {
  PipelineStats stats;
  const auto start = std::chrono::steady_clock::now();
  Watchdog watchdog(std::chrono::milliseconds(options_.watchdog_ms), [this] {
    std::lock_guard lock(servo_mutex_);
    spdlog::warn("control loop stalled for {} ms: parking the servos", options_.watchdog_ms);
    std::string error;
    if (!servos_.Park(&error)) spdlog::error("watchdog could not park the servos: {}", error);
  });
  std::uint64_t grab_errors = 0;
  std::string capture_error;
  std::thread capture([this, &grab_errors, &capture_error] {
    PipelineStats capture_stats;
    CaptureThread(&capture_stats);
    grab_errors = capture_stats.grab_errors;
    capture_error = capture_stats.error;
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
  if (stats.error.empty()) stats.error = capture_error;
  std::string error;
  std::lock_guard lock(servo_mutex_);
  if (!servos_.Park(&error)) spdlog::warn("could not park the servos at the end: {}", error);
  return stats;
}

void Pipeline::RequestCameraChange(std::function<void(FrameSource&)> change) {
  std::lock_guard lock(camera_mutex_);
  camera_changes_.push_back(std::move(change));
}

void Pipeline::CaptureThread(PipelineStats* stats) {
  while (!stop_) {
    std::vector<std::function<void(FrameSource&)>> changes;
    {
      std::lock_guard lock(camera_mutex_);
      std::swap(changes, camera_changes_);
    }
    for (const auto& change : changes) change(source_);
    CapturedFrame frame;
    std::string error;
    if (!source_.Grab(&frame, &error)) {
      // The agent's reconnect with back-off is not built yet: a lost camera ends the run.
      ++stats->grab_errors;
      stats->error = error;
      spdlog::error("capture: {}", error);
      break;
    }
    const std::uint64_t index = frame.index;
    slot_.Put(std::move(frame));
    if (options_.lock_step && !slot_.WaitDone(index)) break;
  }
  slot_.Close();
}

ServoTargets Pipeline::SeenThrough(std::uint64_t index) const {
  const auto delay = static_cast<std::uint64_t>(options_.actuation_delay_frames);
  ServoTargets seen{servos_.limits(ServoAxis::kPan).park_deg,
                    servos_.limits(ServoAxis::kTilt).park_deg};
  if (index < delay) return seen;
  for (auto it = commanded_.rbegin(); it != commanded_.rend(); ++it) {
    if (it->first <= index - delay) return it->second;
  }
  return seen;
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

    const ServoTargets current = SeenThrough(frame->index);
    const FrameOutcome outcome = processor_.Process(*frame, current, dt_s);
    const FixationLoop::Step& step = outcome.step;
    ServoTargets angles;
    {
      std::lock_guard lock(servo_mutex_);
      std::string error;
      if (!servos_.SetAngle(ServoAxis::kPan, step.targets.pan_deg, &error)) ++stats->servo_errors;
      if (!servos_.SetAngle(ServoAxis::kTilt, step.targets.tilt_deg, &error)) {
        ++stats->servo_errors;
      }
      angles = {servos_.angle(ServoAxis::kPan), servos_.angle(ServoAxis::kTilt)};
    }
    commanded_.emplace_back(frame->index, angles);
    if (commanded_.size() > kCommandHistory) commanded_.pop_front();

    TelemetryRecord record;
    record.index = frame->index;
    record.capture_time_us = frame->capture_time_us;
    record.found = step.match.found;
    record.displacement_x_px = step.match.displacement.x;
    record.displacement_y_px = step.match.displacement.y;
    record.confidence = step.match.confidence;
    record.lock_lost = step.lock_lost;
    record.target_pan_deg = step.targets.pan_deg;
    record.target_tilt_deg = step.targets.tilt_deg;
    record.angle_pan_deg = angles.pan_deg;
    record.angle_tilt_deg = angles.tilt_deg;
    record.loop_latency_ms = MsSince(start);
    record.mode = outcome.mode;
    record.slice = outcome.slice;
    record.distance = step.match.distance;
    record.reference_frame = outcome.reference_frame;
    if (options_.view_offset) {
      if (const auto offset = options_.view_offset(frame->index)) {
        record.view_offset_x_px = offset->x;
        record.view_offset_y_px = offset->y;
      }
    }
    for (StepObserver* observer : observers_) observer->OnStep(*frame, outcome, record);
    kick();
    ++stats->processed;
    slot_.MarkDone(frame->index);
    if (options_.frames > 0 && stats->processed >= options_.frames) break;
    if (stop_) break;
  }
  stop_ = true;
  slot_.Close();
}

}  // namespace kapfix::agent
