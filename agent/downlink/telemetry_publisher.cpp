#include "agent/downlink/telemetry_publisher.hpp"

#include <cmath>

#include "agent/downlink/device_health_message.hpp"

namespace kapfix::agent {
namespace {

constexpr double kFpsSmoothing = 1.0 / 30;  // weight of the newest frame interval

void SetDisplacement(double px, std::int32_t* whole, float* sub) {
  const double rounded = std::round(px);
  *whole = static_cast<std::int32_t>(rounded);
  *sub = static_cast<float>(px - rounded);
}

}  // namespace

kapfix::v1::Mode ToProto(AgentMode mode) {
  switch (mode) {
    case AgentMode::kIdle:
      return kapfix::v1::MODE_IDLE;
    case AgentMode::kCalibrate:
      return kapfix::v1::MODE_CALIBRATE;
    case AgentMode::kPss:
      return kapfix::v1::MODE_PSS;
    case AgentMode::kSsp:
      return kapfix::v1::MODE_SSP;
    case AgentMode::kFixate:
      return kapfix::v1::MODE_FIXATE;
    case AgentMode::kFollow:
      return kapfix::v1::MODE_FOLLOW;
    case AgentMode::kRecordFreeSwing:
      return kapfix::v1::MODE_RECORD_FREE_SWING;
  }
  return kapfix::v1::MODE_UNSPECIFIED;
}

std::optional<AgentMode> FromProto(kapfix::v1::Mode mode) {
  switch (mode) {
    case kapfix::v1::MODE_IDLE:
      return AgentMode::kIdle;
    case kapfix::v1::MODE_CALIBRATE:
      return AgentMode::kCalibrate;
    case kapfix::v1::MODE_PSS:
      return AgentMode::kPss;
    case kapfix::v1::MODE_SSP:
      return AgentMode::kSsp;
    case kapfix::v1::MODE_FIXATE:
      return AgentMode::kFixate;
    case kapfix::v1::MODE_FOLLOW:
      return AgentMode::kFollow;
    case kapfix::v1::MODE_RECORD_FREE_SWING:
      return AgentMode::kRecordFreeSwing;
    default:
      return std::nullopt;
  }
}

TelemetryPublisher::TelemetryPublisher(StreamSink& sink,
                                       std::function<std::uint64_t()> video_dropped)
    : sink_(sink), video_dropped_(std::move(video_dropped)) {}

kapfix::v1::Telemetry TelemetryPublisher::ToMessage(const TelemetryRecord& record, double fps,
                                                    std::uint64_t video_dropped,
                                                    std::uint64_t telemetry_dropped) {
  kapfix::v1::Telemetry t;
  t.mutable_header()->set_capture_time_us(record.capture_time_us);
  t.set_frame_number(record.index);
  t.set_mode(ToProto(record.mode));
  auto* d = t.mutable_displacement();
  std::int32_t whole = 0;
  float sub = 0;
  SetDisplacement(record.displacement_x_px, &whole, &sub);
  d->set_x_px(whole);
  d->set_x_subpx(sub);
  SetDisplacement(record.displacement_y_px, &whole, &sub);
  d->set_y_px(whole);
  d->set_y_subpx(sub);
  t.set_confidence(static_cast<float>(record.confidence));
  t.set_distance(record.distance);
  t.set_lock_lost(record.lock_lost);
  t.set_off_target(record.off_target);
  t.set_pan_target_deg(static_cast<float>(record.target_pan_deg));
  t.set_tilt_target_deg(static_cast<float>(record.target_tilt_deg));
  t.set_pan_angle_deg(static_cast<float>(record.angle_pan_deg));
  t.set_tilt_angle_deg(static_cast<float>(record.angle_tilt_deg));
  t.set_fps(static_cast<float>(fps));
  t.set_loop_latency_us(static_cast<std::uint32_t>(std::lround(record.loop_latency_ms * 1000)));
  t.set_video_frames_dropped(video_dropped);
  t.set_telemetry_dropped(telemetry_dropped);
  t.set_slice(static_cast<std::uint32_t>(record.slice));
  *t.mutable_camera_health() = ToProto(record.camera_health);
  *t.mutable_servo_health() = ToProto(record.servo_health);
  if (record.estimate) {
    const ControlEstimate& e = *record.estimate;
    auto* deg_per_px = t.mutable_deg_per_px();
    deg_per_px->set_pan_deg_per_px(static_cast<float>(e.pan.deg_per_px));
    deg_per_px->set_tilt_deg_per_px(static_cast<float>(e.tilt.deg_per_px));
    deg_per_px->set_pan_uncertainty(static_cast<float>(e.pan.relative_sigma));
    deg_per_px->set_tilt_uncertainty(static_cast<float>(e.tilt.relative_sigma));
    // The controller acts on the estimate only where it trusts it: both axes, to say so.
    deg_per_px->set_trusted(e.pan.trusted && e.tilt.trusted);
    t.set_forecast_weight(static_cast<float>(e.forecast_weight()));
  }
  return t;
}

void TelemetryPublisher::OnStep(const CapturedFrame& /*frame*/, const FrameOutcome& /*outcome*/,
                                const TelemetryRecord& record) {
  if (previous_time_us_ && record.capture_time_us > *previous_time_us_) {
    const double rate = 1e6 / static_cast<double>(record.capture_time_us - *previous_time_us_);
    fps_ = fps_ == 0 ? rate : fps_ + kFpsSmoothing * (rate - fps_);
  }
  previous_time_us_ = record.capture_time_us;
  const std::uint64_t video = video_dropped_ ? video_dropped_() : 0;
  if (!sink_.Publish(ToMessage(record, fps_, video, dropped_.load()))) ++dropped_;
}

}  // namespace kapfix::agent
