#include "agent/server/command_validator.hpp"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/unknown_field_set.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <utility>

#include "common/search/search_strategy_names.hpp"

namespace kapfix::agent {
namespace {

using google::protobuf::EnumDescriptor;
using kapfix::v1::Command;
using kapfix::v1::ErrorCode;
using kapfix::v1::Reply;

// Shortest text that reads back as the same value: "0.1", "nan", "-inf", "12".
template <typename T>
std::string Num(T value) {
  std::array<char, 64> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return std::string(buffer.data(), result.ptr);
}

std::string WithUnit(std::string text, std::string_view unit) {
  if (!unit.empty()) {
    text += " [";
    text += unit;
    text += ']';
  }
  return text;
}

enum class Lower { kClosed, kOpen };  // [lo, hi] or (lo, hi]

// Collects the first problem; every later check is skipped once one failed, so the reason
// names exactly one field.
class Checker {
 public:
  bool failed() const { return code_ != kapfix::v1::ERROR_CODE_UNSPECIFIED; }

  void Fail(ErrorCode code, std::string reason) {
    if (failed()) return;
    code_ = code;
    reason_ = std::move(reason);
  }

  void Real(std::string_view field, float value, float lo, float hi, Lower lower,
            std::string_view unit) {
    if (failed()) return;
    const bool finite = std::isfinite(value);
    const bool above_lo = lower == Lower::kOpen ? value > lo : value >= lo;
    if (finite && above_lo && value <= hi) return;
    const std::string range =
        std::string(lower == Lower::kOpen ? "(" : "[") + Num(lo) + ", " + Num(hi) + "]";
    Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE,
         WithUnit(std::string(field) + " = " + Num(value), unit) + ": must be " +
             (finite ? "in " : "a finite number in ") + WithUnit(range, unit));
  }

  void Whole(std::string_view field, std::uint64_t value, std::uint64_t lo, std::uint64_t hi,
             std::string_view unit, std::string_view why = {}) {
    if (failed() || (value >= lo && value <= hi)) return;
    std::string reason = WithUnit(std::string(field) + " = " + Num(value), unit) + ": must be in " +
                         WithUnit("[" + Num(lo) + ", " + Num(hi) + "]", unit);
    if (!why.empty()) reason += std::string(" (") + std::string(why) + ")";
    Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE, std::move(reason));
  }

  // proto3 enums are open: any integer parses, so an unknown value must be refused here.
  // `allow_unspecified`: in a settings update, *_UNSPECIFIED (0) means "leave unchanged".
  void Enum(std::string_view field, int value, const EnumDescriptor& type, bool allow_unspecified) {
    if (failed()) return;
    if (value == 0 && allow_unspecified) return;
    if (value != 0 && type.FindValueByNumber(value) != nullptr) return;
    std::string known;
    for (int i = 0; i < type.value_count(); ++i) {
      if (type.value(i)->number() == 0) continue;
      if (!known.empty()) known += ", ";
      known += type.value(i)->name();
    }
    std::string reason = std::string(field) + " = " + Num(value);
    if (const auto* named = type.FindValueByNumber(value)) reason += " (" + named->name() + ")";
    reason += value == 0 ? ": a value is required, one of " : ": unknown value, must be one of ";
    reason += known;
    Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE, std::move(reason));
  }

  Reply Result() const {
    Reply reply;
    reply.set_ok(!failed());
    reply.set_error(code_);
    reply.set_reason(reason_);
    return reply;
  }

 private:
  ErrorCode code_ = kapfix::v1::ERROR_CODE_UNSPECIFIED;
  std::string reason_;
};

std::uint32_t FrameSide(std::uint32_t side, const CommandLimits& limits) {
  return side == 0 ? limits.fallback_frame_side_px : side;
}

void CheckGains(const kapfix::v1::Gains& gains, const CommandLimits& limits, Checker& check) {
  check.Enum("set_gains.controller", gains.controller(), *kapfix::v1::ControllerKind_descriptor(),
             true);
  if (gains.has_p()) check.Real("set_gains.p", gains.p(), 0, limits.max_p, Lower::kClosed, "1");
  if (gains.has_i()) check.Real("set_gains.i", gains.i(), 0, limits.max_i, Lower::kClosed, "1/s");
  if (gains.has_d()) check.Real("set_gains.d", gains.d(), 0, limits.max_d, Lower::kClosed, "s");
  if (gains.has_dead_band_px()) {
    check.Real("set_gains.dead_band_px", gains.dead_band_px(), 0, limits.max_dead_band_px,
               Lower::kClosed, "px");
  }
  if (gains.has_rate_limit_deg_per_s()) {
    // 0 would freeze the servos: "stop" is a mode (idle), not a rate.
    check.Real("set_gains.rate_limit_deg_per_s", gains.rate_limit_deg_per_s(), 0,
               limits.max_rate_limit_deg_per_s, Lower::kOpen, "deg/s");
  }
}

void CheckSearch(const kapfix::v1::SearchSettings& search, const kapfix::v1::AgentState& current,
                 const CommandLimits& limits, Checker& check) {
  if (search.has_strategy() && !search.strategy().empty() && !check.failed()) {
    const auto& names = kapfix::SearchStrategyNames();
    if (std::find(names.begin(), names.end(), search.strategy()) == names.end()) {
      std::string known;
      for (const std::string& name : names) known += (known.empty() ? "" : ", ") + name;
      // Echoed only when short, not cut: cutting could split a UTF-8 character, and a reply
      // with invalid UTF-8 would not parse at the station.
      constexpr std::size_t kMaxEchoed = 32;
      const std::string& name = search.strategy();
      check.Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE,
                 "set_search.strategy = " + (name.size() <= kMaxEchoed ? "'" + name + "'" : "…") +
                     ": unknown strategy, must be one of " + known);
    }
  }
  check.Enum("set_search.sampling", search.sampling(), *kapfix::v1::Sampling_descriptor(), true);
  if (search.has_random_fraction()) {
    check.Real("set_search.random_fraction", search.random_fraction(), 0, 1, Lower::kOpen, "1");
  }
  const std::uint32_t width = FrameSide(current.frame_width_px(), limits);
  const std::uint32_t height = FrameSide(current.frame_height_px(), limits);
  if (search.has_patch_size_px()) {
    check.Whole("set_search.patch_size_px", search.patch_size_px(), limits.min_patch_size_px,
                std::min(width, height), "px", "the patch must fit in the frame");
  }
  if (search.has_slice_count()) {
    check.Whole("set_search.slice_count", search.slice_count(), 1,
                std::min(limits.max_slice_count, height), "count");
  }
  check.Enum("set_search.axis", search.axis(), *kapfix::v1::Axis_descriptor(), true);
  if (search.has_search_range_px()) {
    check.Whole("set_search.search_range_px", search.search_range_px(), 1, std::max(width, height),
                "px", "shifts beyond the frame find nothing");
  }
  check.Enum("set_search.channel", search.channel(), *kapfix::v1::Channel_descriptor(), true);
  check.Enum("set_search.slice_score", search.slice_score(),
             *kapfix::v1::SliceScoreKind_descriptor(), true);
  if (search.has_dc_hysteresis_px()) {
    check.Real("set_search.dc_hysteresis_px", search.dc_hysteresis_px(), 0,
               limits.max_dc_hysteresis_px, Lower::kClosed, "px");
  }
}

void CheckCamera(const kapfix::v1::CameraSettings& camera, const CommandLimits& limits,
                 Checker& check) {
  if (camera.has_gain_db()) {
    check.Real("set_camera.gain_db", camera.gain_db(), limits.min_gain_db, limits.max_gain_db,
               Lower::kClosed, "dB");
  }
  if (camera.has_exposure_us()) {
    check.Real("set_camera.exposure_us", camera.exposure_us(), 0, limits.max_exposure_us,
               Lower::kOpen, "µs");
  }
}

// The lens name becomes the file name its calibration is stored under: no path separators,
// no hidden or relative names, nothing a shell or a file system could misread.
bool IsSafeName(std::string_view name) {
  if (name.empty() || name.front() == '.') return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '.' ||
           c == '_' || c == '-';
  });
}

void CheckLens(const kapfix::v1::LensProfile& lens, const CommandLimits& limits, Checker& check) {
  if (lens.has_name() && !lens.name().empty() && !check.failed()) {
    if (lens.name().size() > limits.max_lens_name_chars) {
      check.Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE,
                 "set_lens.name is " + Num(lens.name().size()) + " characters long: at most " +
                     Num(limits.max_lens_name_chars));
    } else if (!IsSafeName(lens.name())) {
      check.Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE,
                 "set_lens.name = '" + lens.name() +
                     "': only letters, digits, '.', '_' and '-', not starting with '.'");
    }
  }
  if (lens.has_focal_length_mm()) {
    check.Real("set_lens.focal_length_mm", lens.focal_length_mm(), 0, limits.max_focal_length_mm,
               Lower::kOpen, "mm");
  }
  if (lens.has_pixel_pitch_um()) {
    check.Real("set_lens.pixel_pitch_um", lens.pixel_pitch_um(), 0, limits.max_pixel_pitch_um,
               Lower::kOpen, "µm");
  }
}

void CheckMode(const kapfix::v1::SetMode& set_mode, const CommandLimits& limits, Checker& check) {
  // A mode switch must name a mode: UNSPECIFIED here would mean nothing.
  check.Enum("set_mode.mode", set_mode.mode(), *kapfix::v1::Mode_descriptor(), false);
  if (set_mode.has_deadline_frames()) {
    check.Whole("set_mode.deadline_frames", set_mode.deadline_frames(), 1,
                limits.max_deadline_frames, "frames");
  }
  if (set_mode.has_deadline_s()) {
    check.Real("set_mode.deadline_s", set_mode.deadline_s(), 0, limits.max_deadline_s, Lower::kOpen,
               "s");
  }
}

void CheckVideo(const kapfix::v1::VideoSettings& video, const CommandLimits& limits,
                Checker& check) {
  // fps 0 is allowed: VideoSettings documents it as "video off".
  if (video.has_fps()) {
    check.Real("set_video.fps", video.fps(), 0, limits.max_video_fps, Lower::kClosed, "fps");
  }
  if (video.has_jpeg_quality()) {
    check.Whole("set_video.jpeg_quality", video.jpeg_quality(), 1, 100, "");
  }
  if (video.has_scale()) {
    check.Real("set_video.scale", video.scale(), 0, 1, Lower::kOpen, "1");
  }
}

void CheckPhotoInterval(float interval_s, const CommandLimits& limits, Checker& check) {
  if (interval_s == 0.0F) return;  // off
  if (std::isfinite(interval_s) && interval_s >= limits.min_photo_interval_s &&
      interval_s <= limits.max_photo_interval_s) {
    return;
  }
  check.Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE,
             "set_photo_interval_s = " + Num(interval_s) + " [s]: must be 0 (off) or a finite " +
                 "number in [" + Num(limits.min_photo_interval_s) + ", " +
                 Num(limits.max_photo_interval_s) + "] [s]");
}

// A command field this build does not know arrives as an unknown field (a newer station):
// name its number so the operator can tell which side is out of date.
std::string UnknownCommandReason(const Command& command) {
  const auto& unknown = command.GetReflection()->GetUnknownFields(command);
  for (int i = 0; i < unknown.field_count(); ++i) {
    const int number = unknown.field(i).number();
    if (number != Command::kHeaderFieldNumber) {
      return "unknown command: field " + Num(number) +
             " is not a command this agent knows (it speaks kapfix.v1 up to field " +
             Num(Command::kSetVideoFieldNumber) + ")";
    }
  }
  return "unknown command: the command carries no command field";
}

}  // namespace

CommandValidator::CommandValidator(CommandLimits limits) : limits_(limits) {}

Reply CommandValidator::Validate(const Command& command,
                                 const kapfix::v1::AgentState& current) const {
  Checker check;
  switch (command.command_case()) {
    case Command::kSetMode:
      CheckMode(command.set_mode(), limits_, check);
      break;
    case Command::kSetGains:
      CheckGains(command.set_gains(), limits_, check);
      break;
    case Command::kSetSearch:
      CheckSearch(command.set_search(), current, limits_, check);
      break;
    case Command::kSelectSlice: {
      const std::uint32_t slices = current.search().slice_count() == 0
                                       ? limits_.fallback_slice_count
                                       : current.search().slice_count();
      check.Whole("select_slice", command.select_slice(), 1, slices, "",
                  "1 = top slice, up to the slice count");
      break;
    }
    case Command::kSetCamera:
      CheckCamera(command.set_camera(), limits_, check);
      break;
    case Command::kSetLens:
      CheckLens(command.set_lens(), limits_, check);
      break;
    case Command::kTakePhoto:
      if (command.take_photo().note().size() > limits_.max_photo_note_bytes) {
        check.Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE,
                   "take_photo.note is " + Num(command.take_photo().note().size()) +
                       " bytes long: at most " + Num(limits_.max_photo_note_bytes));
      }
      break;
    case Command::kSetPhotoIntervalS:
      CheckPhotoInterval(command.set_photo_interval_s(), limits_, check);
      break;
    case Command::kRequestState:
      if (command.request_state().resend_photos_since_us() < 0) {
        check.Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE,
                   "request_state.resend_photos_since_us = " +
                       Num(command.request_state().resend_photos_since_us()) +
                       " [µs since epoch]: must be ≥ 0 (0 = none)");
      }
      break;
    case Command::kSetVideo:
      CheckVideo(command.set_video(), limits_, check);
      break;
    case Command::COMMAND_NOT_SET:
      check.Fail(kapfix::v1::ERROR_CODE_UNKNOWN_COMMAND, UnknownCommandReason(command));
      break;
  }
  return check.Result();
}

}  // namespace kapfix::agent
