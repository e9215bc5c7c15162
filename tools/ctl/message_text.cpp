#include "tools/ctl/message_text.hpp"

#include <google/protobuf/descriptor.h>

#include <cctype>
#include <sstream>

#include "kapfix/v1/settings_schema.hpp"

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

// "gains: controller=predictive p=0.8 …": every field of one settings message; enums by
// their word, switches as 1 or 0.
std::string SettingsLine(const char* name, const google::protobuf::Message& settings) {
  using google::protobuf::FieldDescriptor;
  std::ostringstream out;
  out << name << ":";
  const auto& type = *settings.GetDescriptor();
  const auto& r = *settings.GetReflection();
  for (int i = 0; i < type.field_count(); ++i) {
    const FieldDescriptor& field = *type.field(i);
    out << " " << field.name() << "=";
    switch (field.cpp_type()) {
      case FieldDescriptor::CPPTYPE_FLOAT:
        out << r.GetFloat(settings, &field);
        break;
      case FieldDescriptor::CPPTYPE_UINT32:
        out << r.GetUInt32(settings, &field);
        break;
      case FieldDescriptor::CPPTYPE_BOOL:
        out << (r.GetBool(settings, &field) ? 1 : 0);
        break;
      case FieldDescriptor::CPPTYPE_STRING:
        out << r.GetString(settings, &field);
        break;
      case FieldDescriptor::CPPTYPE_ENUM: {
        const auto* value = r.GetEnum(settings, &field);
        const std::string word = kapfix::v1::SettingWord(*value);
        out << (word.empty() ? std::to_string(value->number()) : word);
        break;
      }
      default:
        out << "?";
        break;
    }
  }
  out << "\n";
  return out.str();
}

}  // namespace

std::string ModeWord(kapfix::v1::Mode mode) {
  return EnumWord(*kapfix::v1::Mode_descriptor(), mode, "MODE_");
}

std::string DeviceHealthWord(kapfix::v1::DeviceStatus status) {
  if (status == kapfix::v1::DEVICE_STATUS_UNSPECIFIED) return "unknown";
  return EnumWord(*kapfix::v1::DeviceStatus_descriptor(), status, "DEVICE_");
}

std::string StateText(const kapfix::v1::AgentState& state) {
  std::ostringstream out;
  const auto& search = state.search();
  out << "agent: id=" << state.header().agent_id() << " version=" << state.agent_version()
      << " simulated=" << (state.simulated() ? 1 : 0) << " frame=" << state.frame_width_px() << "x"
      << state.frame_height_px() << " photos_stored=" << state.photos_stored() << "\n";
  out << "mode: " << ModeWord(state.mode()) << "\n";
  // One line per device: "camera: waiting reason=…"; the reason is the rest of the line.
  for (const auto& [name, health] :
       {std::pair<const char*, const kapfix::v1::DeviceHealth&>{"camera", state.camera_health()},
        std::pair<const char*, const kapfix::v1::DeviceHealth&>{"servos", state.servo_health()}}) {
    out << name << ": " << DeviceHealthWord(health.status());
    if (!health.reason().empty()) out << " reason=" << health.reason();
    out << "\n";
  }
  out << "slice: " << state.slice() << " of " << search.slice_count() << "\n";
  // The settings, one line per settings message, every field as the schema names it.
  for (const char* name : {"gains", "search", "camera", "lens", "video", "photo"}) {
    const auto* field = state.GetDescriptor()->FindFieldByName(name);
    out << SettingsLine(name, state.GetReflection()->GetMessage(state, field));
  }
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
      << " video_frames_dropped=" << telemetry.video_frames_dropped()
      << " camera=" << DeviceHealthWord(telemetry.camera_health().status())
      << " servos=" << DeviceHealthWord(telemetry.servo_health().status());
  // The online calibration (issue 9), when the controller keeps one.
  if (telemetry.has_deg_per_px()) {
    const auto& e = telemetry.deg_per_px();
    out << " deg_per_px=" << e.pan_deg_per_px() << "/" << e.tilt_deg_per_px()
        << " uncertainty=" << e.pan_uncertainty() << "/" << e.tilt_uncertainty()
        << " deg_per_px_trusted=" << (e.trusted() ? 1 : 0)
        << " forecast_weight=" << telemetry.forecast_weight();
  }
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
