#include "agent/config/search_config.hpp"

#include <algorithm>
#include <tuple>

#include "kapfix/v1/command.pb.h"
#include "kapfix/v1/settings.pb.h"
#include "kapfix/v1/settings_schema.hpp"

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
  // The ranges are the schema's (kapfix.v1.SearchSettings, and SetMode's deadlines for the
  // default swing deadline), shared with the command validator.
  const auto& search = *kapfix::v1::SearchSettings::descriptor();
  const auto& set_mode = *kapfix::v1::SetMode::descriptor();
  for (const auto& [message, field, value, name] : {
           std::tuple{&search, "patch_size_px", static_cast<double>(patch_px), "search.patch_px"},
           std::tuple{&search, "slice_count", static_cast<double>(slices), "search.slices"},
           std::tuple{&search, "search_range_px", static_cast<double>(range_px), "search.range_px"},
           std::tuple{&search, "dc_hysteresis_px", dc_hysteresis_px, "search.dc_hysteresis_px"},
           std::tuple{&search, "random_fraction", sampling.fraction, "search.sampling"},
           std::tuple{&set_mode, "deadline_frames", static_cast<double>(swing_frames),
                      "search.swing_frames"},
           std::tuple{&set_mode, "deadline_s", swing_seconds, "search.swing_seconds"},
       }) {
    reason = kapfix::v1::CheckSetting(*message, field, value, name);
    if (!reason.empty()) return fail(reason);
  }
  SearchOptions options;
  options.range = range_px;
  options.cross_range = std::min(options.cross_range, range_px);
  if (!options.IsValid(&reason)) return fail("search.range_px: " + reason);
  return true;
}

}  // namespace kapfix::agent
