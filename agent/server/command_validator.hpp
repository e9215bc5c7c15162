#pragma once

// Range checks of every field of a Command before anything can reach a servo (SPEC §2.8, §5;
// issue 5). A proto3 message accepts any float, including NaN and ±inf, and any integer in an
// enum field, so nothing a station sends is trusted until it has passed here.

#include <cstdint>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/state.pb.h"

namespace kapfix::agent {

// The accepted ranges. Defaults are generous for the hardware of SPEC §4 (a 1600×1200 camera
// at most, hobby servos) and tight enough that no value can make the loop misbehave.
struct CommandLimits {
  float max_p = 10.0F;                          // [1] proportional gain
  float max_i = 100.0F;                         // [1/s] integral gain
  float max_d = 10.0F;                          // [s] derivative gain
  float max_dead_band_px = 50.0F;               // [px]
  float max_rate_limit_deg_per_s = 1000.0F;     // [deg/s]; the lower bound is > 0
  std::uint32_t min_patch_size_px = 8;          // [px]; the upper bound is the frame's smaller side
  std::uint32_t max_slice_count = 64;           // [count]; also at most the frame height
  std::uint32_t max_deadline_frames = 100'000;  // [frames]
  float max_deadline_s = 3600.0F;               // [s]
  float max_dc_hysteresis_px = 50.0F;           // [px]
  float min_gain_db = 0.0F;                     // [dB]
  float max_gain_db = 48.0F;                    // [dB]
  float max_exposure_us = 10'000'000.0F;        // [µs]; the lower bound is > 0
  float max_focal_length_mm = 1000.0F;          // [mm]; the lower bound is > 0
  float max_pixel_pitch_um = 100.0F;            // [µm]; the lower bound is > 0
  std::uint32_t max_lens_name_chars = 64;       // [chars] the name becomes a file name
  std::uint32_t max_photo_note_bytes = 1024;    // [bytes]
  float min_photo_interval_s = 0.5F;            // [s] when not 0 (off): a photo takes time to save
  float max_photo_interval_s = 86'400.0F;       // [s]
  float max_video_fps = 60.0F;                  // [fps]; 0 = video off
  // Used when the agent's state does not say (frame size 0, no slice count yet).
  std::uint32_t fallback_frame_side_px = 1600;  // [px] largest camera frame of SPEC §1
  std::uint32_t fallback_slice_count = 9;       // [count] the thesis's N
};

class CommandValidator {
 public:
  explicit CommandValidator(CommandLimits limits = {});

  // A Reply with ok = true when every present field is in range. Otherwise ok = false, error
  // ERROR_CODE_UNKNOWN_COMMAND (no command set, or one newer than this agent) or
  // ERROR_CODE_OUT_OF_RANGE, and a reason naming the field, the value and the limit, e.g.
  // "set_gains.p = nan: must be a finite number in [0, 10]". `current` gives what ranges
  // depend on: the frame size (patch size, search range, slice count) and the slice count
  // (select_slice). Header and command_sequence are left to the caller.
  kapfix::v1::Reply Validate(const kapfix::v1::Command& command,
                             const kapfix::v1::AgentState& current) const;

  const CommandLimits& limits() const { return limits_; }

 private:
  CommandLimits limits_;
};

}  // namespace kapfix::agent
