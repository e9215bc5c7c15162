#pragma once

#include <memory>
#include <string>
#include <string_view>

#include "common/search/hierarchical_search.hpp"
#include "common/search/search_strategy.hpp"

namespace kapfix {

// A hierarchical preset exactly as the thesis runs it (§4.4, Tables 4.5–4.8), beside
// HierarchicalSearch, which answers with the lowest distance seen on any level and may refine
// it: here each level moves the centre to its own least distance, the answer is level 3's
// least distance whatever earlier levels saw, there is no sub-pixel refinement or descent, and
// `evaluations` counts every listed offset scored, as the thesis names its presets (h23 scores
// 23 offsets though level 2 and 3 revisit their centre). SearchOptions::subpixel is ignored.
// Ties within a level go to the offset listed first.
class LiteralHierarchicalSearch final : public SearchStrategy {
 public:
  explicit LiteralHierarchicalSearch(HierarchicalPreset preset);
  std::string name() const override { return preset_.name; }
  SearchResult Search(const ReferencePatch& reference, const cv::Mat& current,
                      const SearchOptions& options) const override;

 private:
  HierarchicalPreset preset_;
};

// The thesis's strategies in their literal form: "all" (exhaustive, integer answer) and the
// presets h23 … h15. Refused with the reason (nullptr, *error set): "pyr" (not in the thesis),
// unknown names, sub-pixel refinement and a search along both axes (the thesis searched one
// axis: X for the kite).
std::unique_ptr<SearchStrategy> MakeLiteralSearchStrategy(std::string_view name,
                                                          const SearchOptions& options,
                                                          std::string* error);

}  // namespace kapfix
