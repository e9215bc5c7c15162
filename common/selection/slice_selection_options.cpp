#include "common/selection/slice_selection_options.hpp"

#include <cmath>

namespace kapfix {
namespace {

bool Fail(std::string* error, const std::string& reason) {
  if (error) *error = reason;
  return false;
}

}  // namespace

bool SliceSelectionOptions::IsValid(std::string* error) const {
  // The upper bounds only catch nonsense; SlicePatch checks them against the real frame.
  if (slice_count < 1 || slice_count > 1000) {
    return Fail(error, "slice count must be 1…1000, got " + std::to_string(slice_count));
  }
  if (patch_size < 1) {
    return Fail(error, "patch size must be ≥ 1 px, got " + std::to_string(patch_size));
  }
  if (!sampling.IsValid(error) || !search.IsValid(error)) return false;
  if (!std::isfinite(hysteresis_px) || hysteresis_px < 0.0) {
    return Fail(error, "hysteresis must be ≥ 0 px, got " + std::to_string(hysteresis_px));
  }
  if (deadline_frames < 0 || deadline_frames == 1) {
    return Fail(error, "deadline must be 0 (none) or ≥ 2 frames (one displacement), got " +
                           std::to_string(deadline_frames));
  }
  if (!std::isfinite(deadline_seconds) || deadline_seconds < 0.0) {
    return Fail(error,
                "deadline must be ≥ 0 s (0 = none), got " + std::to_string(deadline_seconds));
  }
  return true;
}

}  // namespace kapfix
