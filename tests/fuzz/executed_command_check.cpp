#include "tests/fuzz/executed_command_check.hpp"

#include <google/protobuf/descriptor.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "common/search/search_strategy_names.hpp"
#include "tests/fuzz/invariant.hpp"

namespace kapfix::fuzz {
namespace {

using google::protobuf::FieldDescriptor;
using google::protobuf::Message;
using kapfix::agent::CommandLimits;

struct Range {
  std::string_view field;  // full name, e.g. "kapfix.v1.Gains.p"
  double lo;
  double hi;
  bool open_below;  // (lo, hi] rather than [lo, hi]
};

// Every float a command can carry and the range the agent accepts for it. A float field
// missing here breaks the check: a new one needs its limit, here and in CommandValidator.
std::array<Range, 15> FloatRanges(const CommandLimits& l) {
  return {{
      {"kapfix.v1.Gains.p", 0, l.max_p, false},
      {"kapfix.v1.Gains.i", 0, l.max_i, false},
      {"kapfix.v1.Gains.d", 0, l.max_d, false},
      {"kapfix.v1.Gains.dead_band_px", 0, l.max_dead_band_px, false},
      {"kapfix.v1.Gains.rate_limit_deg_per_s", 0, l.max_rate_limit_deg_per_s, true},
      {"kapfix.v1.SearchSettings.random_fraction", 0, 1, true},
      {"kapfix.v1.SearchSettings.dc_hysteresis_px", 0, l.max_dc_hysteresis_px, false},
      {"kapfix.v1.CameraSettings.gain_db", l.min_gain_db, l.max_gain_db, false},
      {"kapfix.v1.CameraSettings.exposure_us", 0, l.max_exposure_us, true},
      {"kapfix.v1.LensProfile.focal_length_mm", 0, l.max_focal_length_mm, true},
      {"kapfix.v1.LensProfile.pixel_pitch_um", 0, l.max_pixel_pitch_um, true},
      {"kapfix.v1.SetMode.deadline_s", 0, l.max_deadline_s, true},
      {"kapfix.v1.VideoSettings.fps", 0, l.max_video_fps, false},
      {"kapfix.v1.VideoSettings.scale", 0, 1, true},
      // 0 (off) or at least min_photo_interval_s: the lower part is checked on its own.
      {"kapfix.v1.Command.set_photo_interval_s", 0, l.max_photo_interval_s, false},
  }};
}

void RequireFloatInRange(const FieldDescriptor& field, double value,
                         const std::array<Range, 15>& ranges) {
  const auto range = std::find_if(ranges.begin(), ranges.end(),
                                  [&](const Range& r) { return r.field == field.full_name(); });
  if (range == ranges.end()) {
    Broken(field.full_name() + " reached the agent but the check knows no limit for it");
  }
  const bool above = range->open_below ? value > range->lo : value >= range->lo;
  if (!std::isfinite(value) || !above || value > range->hi) {
    Broken(field.full_name() + " = " + std::to_string(value) + " reached the agent out of range");
  }
}

// Walks every field present: floats finite and in range, enums known; integers and strings
// are checked by name in RequireSizesFit.
void RequireFieldsKnownAndFinite(const Message& message, const std::array<Range, 15>& ranges) {
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
        RequireFloatInRange(*field, reflection.GetFloat(message, field), ranges);
        break;
      case FieldDescriptor::CPPTYPE_DOUBLE:
        RequireFloatInRange(*field, reflection.GetDouble(message, field), ranges);
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
        RequireFieldsKnownAndFinite(reflection.GetMessage(message, field), ranges);
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
    if (set_mode.has_deadline_frames()) {
      RequireBetween(set_mode.deadline_frames(), 1, l.max_deadline_frames,
                     "set_mode.deadline_frames within limits");
    }
  }
  if (command.has_set_search()) {
    const auto& search = command.set_search();
    if (search.has_strategy() && !search.strategy().empty()) {
      const auto& names = kapfix::SearchStrategyNames();
      Require(std::find(names.begin(), names.end(), search.strategy()) != names.end(),
              "set_search.strategy is a known strategy");
    }
    if (search.has_patch_size_px()) {
      RequireBetween(search.patch_size_px(), l.min_patch_size_px, std::min(width, height),
                     "set_search.patch_size_px fits the frame");
    }
    if (search.has_slice_count()) {
      RequireBetween(search.slice_count(), 1, std::min(l.max_slice_count, height),
                     "set_search.slice_count within limits and frame height");
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
  if (command.has_set_video() && command.set_video().has_jpeg_quality()) {
    RequireBetween(command.set_video().jpeg_quality(), 1, 100,
                   "set_video.jpeg_quality in [1, 100]");
  }
  if (command.has_take_photo()) {
    Require(command.take_photo().note().size() <= l.max_photo_note_bytes,
            "take_photo.note within its length limit");
  }
  if (command.has_set_photo_interval_s()) {
    const float interval = command.set_photo_interval_s();
    Require(interval == 0.0F || interval >= l.min_photo_interval_s,
            "set_photo_interval_s is 0 (off) or at least the shortest interval");
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
  RequireFieldsKnownAndFinite(command, FloatRanges(limits));
  RequireSizesFit(command, before, limits);
}

}  // namespace kapfix::fuzz
