#include "agent/config/search_config.hpp"

#include <algorithm>
#include <tuple>

#include "agent/config/options_from_settings.hpp"
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
  kapfix::v1::SearchSettings settings;
  if (!WriteSettings(*this, &settings, &reason)) return fail("search: " + reason);
  reason = kapfix::v1::CheckSettings(settings, "search");
  if (!reason.empty()) return fail(reason);
  const auto& set_mode = *kapfix::v1::SetMode::descriptor();
  for (const auto& [field, value, name] : {
           std::tuple{"deadline_frames", static_cast<double>(swing_frames), "search.swing_frames"},
           std::tuple{"deadline_s", swing_seconds, "search.swing_seconds"},
       }) {
    reason = kapfix::v1::CheckSetting(set_mode, field, value, name);
    if (!reason.empty()) return fail(reason);
  }
  SearchOptions options;
  options.range = range_px;
  options.cross_range = std::min(options.cross_range, range_px);
  if (!options.IsValid(&reason)) return fail("search.range_px: " + reason);
  return true;
}

std::optional<SamplingKind> SearchConfig::SamplingKindOfWord(std::string_view word) {
  if (word == "all") return SamplingKind::kAll;
  if (word == "static") return SamplingKind::kStatic;
  if (word == "random") return SamplingKind::kRandom;
  return std::nullopt;
}

std::optional<SliceScoreKind> SearchConfig::SliceScoreOfWord(std::string_view word) {
  // The schema's words spell out what common/ abbreviates ("dc-hyst").
  if (word == "dc_hysteresis") return SliceScoreKind::kDcHysteresis;
  if (word == "single_shot") return SliceScoreKind::kSingleShot;
  return ParseSliceScoreKind(word);
}

}  // namespace kapfix::agent
