#include "agent/config/search_config.hpp"

#include <algorithm>

namespace kapfix::agent {

bool SearchConfig::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  const auto& names = SearchStrategyNames();
  if (std::find(names.begin(), names.end(), strategy) == names.end()) {
    return fail("search.strategy: unknown '" + strategy +
                "' (all, h23, h21, h19, h17, h15 or pyr)");
  }
  std::string reason;
  if (!sampling.IsValid(&reason)) return fail("search.sampling: " + reason);
  if (patch_px < 8 || patch_px > 1000) {
    return fail("search.patch_px: must be 8…1000 px, got " + std::to_string(patch_px));
  }
  if (slices < 1 || slices > 64) {
    return fail("search.slices: must be 1…64, got " + std::to_string(slices));
  }
  if (!(dc_hysteresis_px >= 0 && dc_hysteresis_px <= 100)) {
    return fail("search.dc_hysteresis_px: must be 0…100 px, got " +
                std::to_string(dc_hysteresis_px));
  }
  if (swing_frames < 2 || swing_frames > 100000) {
    return fail("search.swing_frames: must be 2…100000, got " + std::to_string(swing_frames));
  }
  if (!(swing_seconds >= 0.1 && swing_seconds <= 3600)) {
    return fail("search.swing_seconds: must be 0.1…3600 s, got " + std::to_string(swing_seconds));
  }
  SearchOptions options;
  options.range = range_px;
  options.cross_range = std::min(options.cross_range, range_px);
  if (!options.IsValid(&reason)) return fail("search.range_px: " + reason);
  return true;
}

}  // namespace kapfix::agent
