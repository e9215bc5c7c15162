#include "tools/ctl/message_text.hpp"

#include <google/protobuf/descriptor.h>

#include <cctype>
#include <sstream>

namespace kapfix::ctl {
namespace {

// "MODE_FIXATE" with prefix "MODE_" → "fixate"; unknown numbers print as numbers.
std::string EnumWord(const google::protobuf::EnumDescriptor& type, int value,
                     const std::string& prefix) {
  const auto* named = type.FindValueByNumber(value);
  if (named == nullptr) return std::to_string(value);
  std::string word = named->name();
  if (word.rfind(prefix, 0) == 0) word.erase(0, prefix.size());
  for (char& c : word) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return word;
}

}  // namespace

std::string ModeWord(kapfix::v1::Mode mode) {
  return EnumWord(*kapfix::v1::Mode_descriptor(), mode, "MODE_");
}

std::string StateText(const kapfix::v1::AgentState& state) {
  std::ostringstream out;
  const auto& gains = state.gains();
  const auto& search = state.search();
  const auto& camera = state.camera();
  const auto& lens = state.lens();
  const auto& video = state.video();
  out << "agent: id=" << state.header().agent_id() << " version=" << state.agent_version()
      << " simulated=" << (state.simulated() ? 1 : 0) << " frame=" << state.frame_width_px() << "x"
      << state.frame_height_px() << " photos_stored=" << state.photos_stored() << "\n";
  out << "mode: " << ModeWord(state.mode()) << "\n";
  out << "slice: " << state.slice() << " of " << search.slice_count() << "\n";
  out << "gains: controller="
      << EnumWord(*kapfix::v1::ControllerKind_descriptor(), gains.controller(), "CONTROLLER_KIND_")
      << " p=" << gains.p() << " i=" << gains.i() << " d=" << gains.d()
      << " dead_band_px=" << gains.dead_band_px()
      << " rate_limit_deg_per_s=" << gains.rate_limit_deg_per_s() << "\n";
  out << "search: strategy=" << search.strategy() << " sampling="
      << EnumWord(*kapfix::v1::Sampling_descriptor(), search.sampling(), "SAMPLING_")
      << " random_fraction=" << search.random_fraction()
      << " patch_size_px=" << search.patch_size_px() << " slice_count=" << search.slice_count()
      << " axis=" << EnumWord(*kapfix::v1::Axis_descriptor(), search.axis(), "AXIS_")
      << " search_range_px=" << search.search_range_px()
      << " subpixel=" << (search.subpixel() ? 1 : 0)
      << " channel=" << EnumWord(*kapfix::v1::Channel_descriptor(), search.channel(), "CHANNEL_")
      << " slice_score="
      << EnumWord(*kapfix::v1::SliceScoreKind_descriptor(), search.slice_score(),
                  "SLICE_SCORE_KIND_")
      << " dc_hysteresis_px=" << search.dc_hysteresis_px() << "\n";
  out << "camera: gain_db=" << camera.gain_db() << " exposure_us=" << camera.exposure_us()
      << " auto_exposure=" << (camera.auto_exposure() ? 1 : 0) << "\n";
  out << "lens: name=" << lens.name() << " focal_length_mm=" << lens.focal_length_mm()
      << " pixel_pitch_um=" << lens.pixel_pitch_um() << "\n";
  out << "video: fps=" << video.fps() << " jpeg_quality=" << video.jpeg_quality()
      << " scale=" << video.scale() << "\n";
  out << "photo_interval_s: " << state.photo_interval_s() << "\n";
  if (state.has_last_slice_report()) {
    out << "last_ssp: recommended_slice=" << state.last_slice_report().recommended_slice()
        << " finished=" << (state.last_slice_report().finished() ? 1 : 0) << "\n";
  }
  return out.str();
}

std::string TelemetryText(const kapfix::v1::Telemetry& telemetry) {
  std::ostringstream out;
  const auto& d = telemetry.displacement();
  out << "telemetry seq=" << telemetry.header().sequence() << " frame=" << telemetry.frame_number()
      << " mode=" << ModeWord(telemetry.mode())
      << " dx=" << (static_cast<double>(d.x_px()) + d.x_subpx())
      << " dy=" << (static_cast<double>(d.y_px()) + d.y_subpx())
      << " confidence=" << telemetry.confidence()
      << " lock_lost=" << (telemetry.lock_lost() ? 1 : 0) << " slice=" << telemetry.slice()
      << " pan_deg=" << telemetry.pan_angle_deg() << " tilt_deg=" << telemetry.tilt_angle_deg()
      << " fps=" << telemetry.fps() << " loop_latency_us=" << telemetry.loop_latency_us()
      << " telemetry_dropped=" << telemetry.telemetry_dropped()
      << " video_frames_dropped=" << telemetry.video_frames_dropped();
  return out.str();
}

std::string SliceReportText(const kapfix::v1::SliceReport& report) {
  std::ostringstream out;
  if (!report.finished()) {
    out << "ssp progress=" << report.progress_done() << "/" << report.progress_total();
    return out.str();
  }
  for (const auto& slice : report.slices()) {
    out << "slice index=" << slice.index() << " rank=" << slice.rank() << " dc=" << slice.dc()
        << " dc_hysteresis=" << slice.dc_hysteresis() << " fft=" << slice.fft()
        << " single_shot=" << slice.single_shot() << "\n";
  }
  out << "recommended_slice: " << report.recommended_slice()
      << (report.deadline_reached() ? " (deadline reached)" : "");
  return out.str();
}

}  // namespace kapfix::ctl
