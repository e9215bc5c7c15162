#include "agent/server/command_validator.hpp"

#include <google/protobuf/descriptor.h>
#include <google/protobuf/unknown_field_set.h>

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <memory>
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

std::uint32_t FrameSide(std::uint32_t side, const CommandLimits& limits) {
  return side == 0 ? limits.fallback_frame_side_px : side;
}

// A numeric field's value, absent or not (absent reads 0).
double NumberOf(const google::protobuf::Message& settings,
                const google::protobuf::FieldDescriptor& field) {
  const auto& r = *settings.GetReflection();
  switch (field.cpp_type()) {
    case google::protobuf::FieldDescriptor::CPPTYPE_FLOAT:
      return r.GetFloat(settings, &field);
    case google::protobuf::FieldDescriptor::CPPTYPE_DOUBLE:
      return r.GetDouble(settings, &field);
    case google::protobuf::FieldDescriptor::CPPTYPE_INT32:
      return r.GetInt32(settings, &field);
    case google::protobuf::FieldDescriptor::CPPTYPE_UINT32:
      return r.GetUInt32(settings, &field);
    default:
      return 0;
  }
}

// "5 s": the value as the field holds it (a float shows as the float it is) and its unit.
std::string ValueText(const google::protobuf::FieldDescriptor& field, double value,
                      const kapfix::v1::SettingOptions& options) {
  const std::string number = field.cpp_type() == google::protobuf::FieldDescriptor::CPPTYPE_FLOAT
                                 ? Num(static_cast<float>(value))
                                 : Num(value);
  return options.unit().empty() || options.unit() == "1" ? number : number + " " + options.unit();
}

// The agent's current settings of `settings`' type from its state, the schema's initial values
// for those it has not reported yet.
std::unique_ptr<google::protobuf::Message> HeldSettings(const google::protobuf::Message& settings,
                                                        const kapfix::v1::AgentState& current) {
  std::unique_ptr<google::protobuf::Message> held(settings.New());
  std::string ignored;  // a bad initial value is the schema test's to catch
  kapfix::v1::SetInitialSettings(held.get(), &ignored);
  const google::protobuf::Descriptor& state = *kapfix::v1::AgentState::descriptor();
  for (int i = 0; i < state.field_count(); ++i) {
    if (state.field(i)->message_type() == settings.GetDescriptor()) {
      kapfix::v1::MergeSettings(current.GetReflection()->GetMessage(current, state.field(i)),
                                held.get());
      break;
    }
  }
  return held;
}

// Every present field of a settings command: the schema's range, capped by the agent's frame
// where the field's option names a frame side, and not beyond the field its option's `at_most`
// names (the command's value of it, or the agent's). Nothing here names a setting.
void CheckSettingsCommand(const google::protobuf::Message& settings, std::string_view prefix,
                          const kapfix::v1::AgentState& current, const CommandLimits& limits,
                          Checker& check) {
  check.Settings(settings, prefix);
  const google::protobuf::Descriptor& type = *settings.GetDescriptor();
  const auto& r = *settings.GetReflection();
  const std::uint32_t width = FrameSide(current.frame_width_px(), limits);
  const std::uint32_t height = FrameSide(current.frame_height_px(), limits);
  std::unique_ptr<google::protobuf::Message> held;
  for (int i = 0; i < type.field_count() && !check.failed(); ++i) {
    const google::protobuf::FieldDescriptor& field = *type.field(i);
    const kapfix::v1::SettingOptions* options = kapfix::v1::SettingOf(field);
    if (options == nullptr || field.is_repeated()) continue;
    const std::string path = std::string(prefix) + "." + field.name();
    if (options->frame_side() != kapfix::v1::FRAME_SIDE_UNSPECIFIED &&
        r.HasField(settings, &field)) {
      const std::uint32_t side =
          options->frame_side() == kapfix::v1::FRAME_SIDE_SHORTER  ? std::min(width, height)
          : options->frame_side() == kapfix::v1::FRAME_SIDE_HEIGHT ? height
                                                                   : std::max(width, height);
      kapfix::v1::SettingOptions capped = *options;
      capped.set_max(std::min(capped.max(), static_cast<double>(side)));
      const double value = NumberOf(settings, field);
      if (!kapfix::v1::InRange(value, capped)) {
        check.Reason(kapfix::v1::OutOfRangeReason(path, value, capped) + " (" +
                     options->frame_why() + ")");
      }
    }
    const google::protobuf::FieldDescriptor* bound =
        options->at_most().empty() ? nullptr : type.FindFieldByName(options->at_most());
    if (bound == nullptr || (!r.HasField(settings, &field) && !r.HasField(settings, bound))) {
      continue;
    }
    if (!held) held = HeldSettings(settings, current);
    const auto value_of = [&](const google::protobuf::FieldDescriptor& f) {
      return NumberOf(r.HasField(settings, &f) ? settings : *held, f);
    };
    const double value = value_of(field);
    const double limit = value_of(*bound);
    const kapfix::v1::SettingOptions* bound_options = kapfix::v1::SettingOf(*bound);
    if (value > limit) {
      check.Fail(
          kapfix::v1::ERROR_CODE_OUT_OF_RANGE,
          path + " = " + ValueText(field, value, *options) + " is more than " + bound->name() +
              " = " +
              ValueText(*bound, limit, bound_options != nullptr ? *bound_options : *options) +
              ": " + options->at_most_why());
    }
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
  CheckSettingsCommand(search, "set_search", current, limits, check);
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

void CheckLens(const kapfix::v1::LensProfile& lens, const kapfix::v1::AgentState& current,
               const CommandLimits& limits, Checker& check) {
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
  CheckSettingsCommand(lens, "set_lens", current, limits, check);
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
    if (number == Command::kHeaderFieldNumber) continue;
    const google::protobuf::Descriptor& descriptor = *Command::descriptor();
    if (descriptor.IsReservedNumber(number)) {
      return "unknown command: field " + Num(number) +
             " was removed from kapfix.v1 (the station is older than this agent; see "
             "command.proto)";
    }
    // The highest command field, from the descriptor so that it never goes stale.
    int highest = 0;
    const google::protobuf::OneofDescriptor& commands = *descriptor.oneof_decl(0);
    for (int k = 0; k < commands.field_count(); ++k) {
      highest = std::max(highest, commands.field(k)->number());
    }
    return "unknown command: field " + Num(number) +
           " is not a command this agent knows (it speaks kapfix.v1 up to field " + Num(highest) +
           ")";
  }
  return "unknown command: the command carries no command field";
}

}  // namespace

bool CommandValidator::NeedsState(const kapfix::v1::Command& command) {
  if (command.has_select_slice()) return true;
  const google::protobuf::OneofDescriptor& oneof =
      *kapfix::v1::Command::descriptor()->oneof_decl(0);
  const google::protobuf::FieldDescriptor* set =
      command.GetReflection()->GetOneofFieldDescriptor(command, &oneof);
  if (set == nullptr || set->message_type() == nullptr) return false;
  const google::protobuf::Descriptor& type = *set->message_type();
  for (int i = 0; i < type.field_count(); ++i) {
    const kapfix::v1::SettingOptions* options = kapfix::v1::SettingOf(*type.field(i));
    if (options != nullptr && (options->frame_side() != kapfix::v1::FRAME_SIDE_UNSPECIFIED ||
                               !options->at_most().empty())) {
      return true;
    }
  }
  return false;
}

CommandValidator::CommandValidator(CommandLimits limits) : limits_(limits) {}

Reply CommandValidator::Validate(const Command& command,
                                 const kapfix::v1::AgentState& current) const {
  Checker check;
  switch (command.command_case()) {
    case Command::kSetMode:
      CheckMode(command.set_mode(), check);
      break;
    case Command::kSetGains:
      CheckSettingsCommand(command.set_gains(), "set_gains", current, limits_, check);
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
      CheckSettingsCommand(command.set_camera(), "set_camera", current, limits_, check);
      break;
    case Command::kSetLens:
      CheckLens(command.set_lens(), current, limits_, check);
      break;
    case Command::kTakePhoto:
      if (command.take_photo().note().size() > limits_.max_photo_note_bytes) {
        check.Fail(kapfix::v1::ERROR_CODE_OUT_OF_RANGE,
                   "take_photo.note is " + Num(command.take_photo().note().size()) +
                       " bytes long: at most " + Num(limits_.max_photo_note_bytes));
      }
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
      CheckSettingsCommand(command.set_video(), "set_video", current, limits_, check);
      break;
    case Command::kSetPhoto:
      CheckSettingsCommand(command.set_photo(), "set_photo", current, limits_, check);
      break;
    case Command::COMMAND_NOT_SET:
      check.Fail(kapfix::v1::ERROR_CODE_UNKNOWN_COMMAND, UnknownCommandReason(command));
      break;
  }
  return check.Result();
}

}  // namespace kapfix::agent
