#include "tests/fuzz/executed_command_check.hpp"

#include <google/protobuf/descriptor.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/search/search_strategy_names.hpp"
#include "kapfix/v1/settings_schema.hpp"
#include "tests/fuzz/invariant.hpp"

namespace kapfix::fuzz {
namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using kapfix::agent::CommandLimits;

// The range the agent accepts for a number is its field's option in the settings schema: a
// number that reached the agent must be in it. A numeric command field without one breaks
// the check: a new one needs its range in the .proto.
void RequireNumberInRange(const FieldDescriptor& field, double value) {
  const kapfix::v1::SettingOptions* setting = kapfix::v1::SettingOf(field);
  if (setting == nullptr) {
    Broken(field.full_name() + " reached the agent but the schema gives it no range");
  }
  if (!kapfix::v1::InRange(value, *setting)) {
    Broken(kapfix::v1::OutOfRangeReason(field.full_name(), value, *setting) +
           ", yet it reached the agent");
  }
}

// Walks every field present: floats and the settings' whole numbers finite and in their
// schema range, enums known; other integers and strings are checked by name in
// RequireSizesFit.
void RequireFieldsKnownAndFinite(const Message& message) {
  const auto& reflection = *message.GetReflection();
  std::vector<const FieldDescriptor*> fields;
  reflection.ListFields(message, &fields);
  for (const FieldDescriptor* field : fields) {
    if (field->full_name() == "kapfix.v1.Command.header") continue;  // checked by the caller
    if (field->is_repeated()) {
      Broken(field->full_name() + " is repeated: no command field was, the check needs updating");
    }
    switch (field->cpp_type()) {
      case FieldDescriptor::CPPTYPE_FLOAT:
        RequireNumberInRange(*field, reflection.GetFloat(message, field));
        break;
      case FieldDescriptor::CPPTYPE_DOUBLE:
        RequireNumberInRange(*field, reflection.GetDouble(message, field));
        break;
      case FieldDescriptor::CPPTYPE_UINT32:
        if (kapfix::v1::SettingOf(*field) != nullptr) {
          RequireNumberInRange(*field, reflection.GetUInt32(message, field));
        }
        break;
      case FieldDescriptor::CPPTYPE_ENUM: {
        // proto3 enums are open: any integer parses, only known values may pass.
        const int value = reflection.GetEnumValue(message, field);
        if (field->enum_type()->FindValueByNumber(value) == nullptr) {
          Broken(field->full_name() + " = " + std::to_string(value) +
                 " reached the agent but is no value of " + field->enum_type()->full_name());
        }
        break;
      }
      case FieldDescriptor::CPPTYPE_MESSAGE:
        RequireFieldsKnownAndFinite(reflection.GetMessage(message, field));
        break;
      default:
        break;
    }
  }
}

void RequireBetween(std::uint64_t value, std::uint64_t lo, std::uint64_t hi, const char* what) {
  Require(value >= lo && value <= hi, what);
}

void RequireSizesFit(const kapfix::v1::Command& command, const kapfix::v1::AgentState& before,
                     const CommandLimits& l) {
  const std::uint32_t width = before.frame_width_px();
  const std::uint32_t height = before.frame_height_px();
  Require(width > 0 && height > 0 && before.search().slice_count() > 0,
          "the state the command was checked against gives frame size and slice count");
  if (command.has_set_mode()) {
    const auto& set_mode = command.set_mode();
    Require(set_mode.mode() != kapfix::v1::MODE_UNSPECIFIED, "set_mode names a mode");
  }
  if (command.has_set_search()) {
    const auto& search = command.set_search();
    if (search.has_strategy() && !search.strategy().empty()) {
      const auto& names = kapfix::SearchStrategyNames();
      Require(std::find(names.begin(), names.end(), search.strategy()) != names.end(),
              "set_search.strategy is a known strategy");
    }
    if (search.has_patch_size_px()) {
      RequireBetween(search.patch_size_px(), 1, std::min(width, height),
                     "set_search.patch_size_px fits the frame");
    }
    if (search.has_slice_count()) {
      RequireBetween(search.slice_count(), 1, height, "set_search.slice_count within the frame");
    }
    if (search.has_search_range_px()) {
      RequireBetween(search.search_range_px(), 1, std::max(width, height),
                     "set_search.search_range_px within the frame");
    }
  }
  if (command.has_select_slice()) {
    RequireBetween(command.select_slice(), 1, before.search().slice_count(),
                   "select_slice names an existing slice");
  }
  if (command.has_set_lens() && command.set_lens().has_name()) {
    // The name becomes a file name: never a path, never hidden.
    const std::string& name = command.set_lens().name();
    Require(name.size() <= l.max_lens_name_chars, "set_lens.name within its length limit");
    Require(name.find_first_of(std::string_view("/\\\0", 3)) == std::string::npos &&
                (name.empty() || name.front() != '.'),
            "set_lens.name is a plain, visible file name");
  }
  if (command.has_take_photo()) {
    Require(command.take_photo().note().size() <= l.max_photo_note_bytes,
            "take_photo.note within its length limit");
  }
  if (command.has_request_state()) {
    Require(command.request_state().resend_photos_since_us() >= 0,
            "request_state.resend_photos_since_us is not negative");
  }
}

}  // namespace

void RequireWithinLimits(const kapfix::v1::Command& command, const kapfix::v1::AgentState& before,
                         const CommandLimits& limits) {
  Require(command.command_case() != kapfix::v1::Command::COMMAND_NOT_SET,
          "an executed command carries a command");
  RequireFieldsKnownAndFinite(command);
  RequireSizesFit(command, before, limits);
}

}  // namespace kapfix::fuzz
