#include "common/search/literal_hierarchical_search.hpp"

#include <cmath>

#include "common/search/axis_probe.hpp"
#include "common/search/exhaustive_search.hpp"

namespace kapfix {

LiteralHierarchicalSearch::LiteralHierarchicalSearch(HierarchicalPreset preset)
    : preset_(std::move(preset)) {}

SearchResult LiteralHierarchicalSearch::Search(const ReferencePatch& reference,
                                               const cv::Mat& current,
                                               const SearchOptions& options) const {
  SearchResult result;
  result.confidence_x = result.confidence_y = 1.0;  // until searched
  cv::Point shift = options.origin;
  double confidence = 1.0;
  int visits = 0;
  for (const bool along_x : {true, false}) {
    if ((along_x && options.axis == SearchAxis::kY) || (!along_x && options.axis == SearchAxis::kX))
      continue;
    // Levels may step past ±R around the centre (level 1's −100 plus level 2's −15).
    AxisProbe probe(reference, current, along_x, shift, 2 * options.range);
    int centre = probe.centre_position();
    std::int64_t answer_distance = -1;
    for (const std::vector<int>& level : preset_.levels) {
      int level_best = centre;
      std::int64_t level_distance = -1;
      for (const int offset : level) {
        const int scaled = options.range == 100
                               ? offset
                               : static_cast<int>(std::lround(offset * options.range / 100.0));
        std::int64_t distance = 0;
        if (!probe.Evaluate(centre + scaled, &distance)) continue;
        ++visits;
        if (level_distance < 0 || distance < level_distance) {
          level_distance = distance;
          level_best = centre + scaled;
        }
      }
      centre = level_best;
      if (level_distance >= 0) answer_distance = level_distance;
    }
    if (answer_distance < 0) return result;  // nothing in the frame could be scored
    (along_x ? shift.x : shift.y) = centre;
    result.distance = answer_distance;
    (along_x ? result.confidence_x : result.confidence_y) = probe.Confidence();
    confidence = std::min(confidence, probe.Confidence());
  }
  result.found = true;
  result.shift = shift;
  result.displacement = cv::Point2d(shift);
  result.confidence = confidence;
  result.evaluations = visits;
  result.pixels_compared = static_cast<std::int64_t>(visits) * reference.size();
  return result;
}

std::unique_ptr<SearchStrategy> MakeLiteralSearchStrategy(std::string_view name,
                                                          const SearchOptions& options,
                                                          std::string* error) {
  auto refuse = [&](const std::string& reason) -> std::unique_ptr<SearchStrategy> {
    if (error) *error = "--literal: " + reason;
    return nullptr;
  };
  if (options.subpixel) {
    return refuse("the thesis's searches answer whole pixels; sub-pixel refinement is ours");
  }
  if (options.axis == SearchAxis::kBoth) {
    return refuse("the thesis searched one axis (x for the kite); a search along both is ours");
  }
  if (name == "pyr") return refuse("'pyr' is not the thesis's strategy, it has no literal form");
  if (name == "all") return std::make_unique<ExhaustiveSearch>();
  for (const HierarchicalPreset& preset : HierarchicalPresets()) {
    if (preset.name == name) return std::make_unique<LiteralHierarchicalSearch>(preset);
  }
  return refuse("unknown strategy '" + std::string(name) + "' (all, h23, h21, h19, h17 or h15)");
}

}  // namespace kapfix
