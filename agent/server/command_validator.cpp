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
#include "kapfix/v1/settings_schema.hpp"

namespace kapfix::agent {
namespace {

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

  // Records `reason` unless it is empty (no problem).
  void Reason(std::string reason) {
    if (!reason.empty()) Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE, std::move(reason));
  }

  // Every setting present in `settings`, against the schema.
  void Settings(const google::protobuf::Message& settings, std::string_view prefix) {
    if (!failed()) Reason(kapfix::v1::CheckSettings(settings, prefix));
  }

  // A whole number whose upper bound depends on the frame: the schema's range, capped.
  void WithinFrame(const google::protobuf::Message& settings, std::string_view field_name,
                   std::uint64_t value, std::uint64_t frame_max, std::string_view prefix,
                   std::string_view why) {
    if (failed()) return;
    const auto* field = kapfix::v1::SettingField(*settings.GetDescriptor(), field_name);
    if (field == nullptr) return;
    kapfix::v1::SettingOptions capped = *kapfix::v1::SettingOf(*field);
    capped.set_max(std::min(capped.max(), static_cast<double>(frame_max)));
    if (kapfix::v1::InRange(static_cast<double>(value), capped)) return;
    Reason(kapfix::v1::OutOfRangeReason(std::string(prefix) + "." + std::string(field_name),
                                        static_cast<double>(value), capped) +
           " (" + std::string(why) + ")");
  }

  // A range with no schema of its own (select_slice: 1 up to the slice count).
  void Whole(std::string_view field, std::uint64_t value, std::uint64_t lo, std::uint64_t hi,
             std::string_view why) {
    if (failed() || (value >= lo && value <= hi)) return;
    Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE, std::string(field) + " = " + Num(value) +
                                                  ": must be in [" + Num(lo) + ", " + Num(hi) +
                                                  "] (" + std::string(why) + ")");
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

// The window may not outlast its cap (issue 13): across two fields, each of which may come
// from the command or keep the agent's current value.
void CheckPhoto(const kapfix::v1::PhotoSettings& photo, const kapfix::v1::AgentState& current,
                Checker& check) {
  check.Settings(photo, "set_photo");
  if (check.failed() || (!photo.has_window_s() && !photo.has_window_cap_s())) return;
  const float window = photo.has_window_s() ? photo.window_s() : current.photo().window_s();
  // An agent that has not said its cap yet: the config's default.
  constexpr float kDefaultCapS = 10;
  const float cap = photo.has_window_cap_s()             ? photo.window_cap_s()
                    : current.photo().has_window_cap_s() ? current.photo().window_cap_s()
                                                         : kDefaultCapS;
  if (window > cap) {
    check.Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE,
               "set_photo.window_s = " + Num(window) + " s is longer than window_cap_s = " +
                   Num(cap) + " s: shorten the window or raise the cap");
  }
}

std::uint32_t FrameSide(std::uint32_t side, const CommandLimits& limits) {
  return side == 0 ? limits.fallback_frame_side_px : side;
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
  check.Settings(search, "set_search");
  const std::uint32_t width = FrameSide(current.frame_width_px(), limits);
  const std::uint32_t height = FrameSide(current.frame_height_px(), limits);
  if (search.has_patch_size_px()) {
    check.WithinFrame(search, "patch_size_px", search.patch_size_px(), std::min(width, height),
                      "set_search", "the patch must fit in the frame");
  }
  if (search.has_slice_count()) {
    check.WithinFrame(search, "slice_count", search.slice_count(), height, "set_search",
                      "a slice is at least one row of the frame");
  }
  if (search.has_search_range_px()) {
    check.WithinFrame(search, "search_range_px", search.search_range_px(), std::max(width, height),
                      "set_search", "shifts beyond the frame find nothing");
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
  check.Settings(lens, "set_lens");
}

void CheckMode(const kapfix::v1::SetMode& set_mode, Checker& check) {
  // A mode switch must name a mode: UNSPECIFIED here would mean nothing.
  if (set_mode.mode() == kapfix::v1::MODE_UNSPECIFIED) {
    std::string known;
    const auto& modes = *kapfix::v1::Mode_descriptor();
    for (int i = 1; i < modes.value_count(); ++i) {
      known += (known.empty() ? "" : ", ") + modes.value(i)->name();
    }
    check.Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE,
               "set_mode.mode = 0 (MODE_UNSPECIFIED): a value is required, one of " + known);
  }
  check.Settings(set_mode, "set_mode");
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
      CheckMode(command.set_mode(), check);
      break;
    case Command::kSetGains:
      check.Settings(command.set_gains(), "set_gains");
      break;
    case Command::kSetSearch:
      CheckSearch(command.set_search(), current, limits_, check);
      break;
    case Command::kSelectSlice: {
      const std::uint32_t slices = current.search().slice_count() == 0
                                       ? limits_.fallback_slice_count
                                       : current.search().slice_count();
      check.Whole("select_slice", command.select_slice(), 1, slices,
                  "1 = top slice, up to the slice count");
      break;
    }
    case Command::kSetCamera:
      check.Settings(command.set_camera(), "set_camera");
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
      check.Settings(command, "");
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
      check.Settings(command.set_video(), "set_video");
      break;
    case Command::kSetPhoto:
      CheckPhoto(command.set_photo(), current, check);
      break;
    case Command::COMMAND_NOT_SET:
      check.Fail(kapfix::v1::ERROR_CODE_UNKNOWN_COMMAND, UnknownCommandReason(command));
      break;
  }
  return check.Result();
}

}  // namespace kapfix::agent
