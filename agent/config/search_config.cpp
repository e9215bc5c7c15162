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
  SearchOptions options;
  options.range = range_px;
  options.cross_range = std::min(options.cross_range, range_px);
  if (!options.IsValid(&reason)) return fail("search.range_px: " + reason);
  return true;
}

}  // namespace kapfix::agent
