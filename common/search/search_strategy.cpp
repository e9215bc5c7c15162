#include "common/search/search_strategy.hpp"

#include "common/search/exhaustive_search.hpp"
#include "common/search/hierarchical_search.hpp"
#include "common/search/pyramid_search.hpp"

namespace kapfix {

std::optional<SearchAxis> ParseSearchAxis(std::string_view text) {
  if (text == "x" || text == "X") return SearchAxis::kX;
  if (text == "y" || text == "Y") return SearchAxis::kY;
  if (text == "both" || text == "xy") return SearchAxis::kBoth;
  return std::nullopt;
}

std::string_view ToString(SearchAxis axis) {
  switch (axis) {
    case SearchAxis::kX:
      return "x";
    case SearchAxis::kY:
      return "y";
    case SearchAxis::kBoth:
      return "both";
  }
  return "?";
}

bool SearchOptions::IsValid(std::string* error) const {
  if (range < 1 || range > 2000) {
    if (error) *error = "search range must be 1…2000 px, got " + std::to_string(range);
    return false;
  }
  if (cross_range < 0 || cross_range > range) {
    if (error) *error = "cross range must be 0…range px, got " + std::to_string(cross_range);
    return false;
  }
  return true;
}

std::unique_ptr<SearchStrategy> MakeSearchStrategy(std::string_view name, std::string* error) {
  if (name == "all") return std::make_unique<ExhaustiveSearch>();
  if (name == "pyr") return std::make_unique<PyramidSearch>();
  for (const HierarchicalPreset& preset : HierarchicalPresets()) {
    if (preset.name == name) return std::make_unique<HierarchicalSearch>(preset);
  }
  if (error) {
    *error =
        "unknown search strategy '" + std::string(name) + "' (all, h23, h21, h19, h17, h15 or pyr)";
  }
  return nullptr;
}

}  // namespace kapfix
