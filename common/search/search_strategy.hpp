#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "common/matching/reference_patch.hpp"
#include "common/search/search_strategy_names.hpp"

namespace kapfix {

// Which axes the search covers (SPEC §2.3): X for a kite (the pendulum swings sideways),
// Y for a boat (it rolls), or both. kBoth is separable: a full 1-D search along X at the
// origin's y, then a full 1-D search along Y at the x found; it costs the sum of the two 1-D
// searches (a joint 2-D search would cost their product).
enum class SearchAxis { kX, kY, kBoth };

std::optional<SearchAxis> ParseSearchAxis(std::string_view text);
std::string_view ToString(SearchAxis axis);

struct SearchOptions {
  SearchAxis axis = SearchAxis::kX;
  int range = 100;         // R [px]: shifts in [origin − R, origin + R]
  bool subpixel = true;    // parabola through the best shift and its two neighbours
  cv::Point origin{0, 0};  // [px] the shift the search is centred on
  // [px] "pyr" only: how far across a single search axis it also looks. A kite's pendulum
  // swings along X but the view still wobbles by a few pixels in Y (SPEC §3: σ = 2 px), and on
  // fine texture that alone moves an X-only minimum by up to tens of pixels. 8 px is 4σ:
  // measured over the 13 benchmark photos, ±4 px still lost 1.3 % of frames, ±8 px 0.04 %.
  // The thesis's strategies stay X-only, as published.
  int cross_range = 8;

  bool IsValid(std::string* error) const;
};

struct SearchResult {
  bool found = false;              // false when no shift inside the frame could be scored
  cv::Point shift{0, 0};           // [px] best integer shift
  cv::Point2d displacement{0, 0};  // [px] shift with its sub-pixel part
  std::int64_t distance = 0;       // SSD at `shift`
  double confidence = 0.0;         // [0, 1] how clearly the minimum beats its best rival
  // [0, 1] the same along each axis alone, 1 on an axis not searched; `confidence` is the
  // lower of the two. A patch of stripes (aloe leaves, a row of columns) is placed surely
  // across them and hardly along them: the aperture problem, which one figure hides.
  double confidence_x = 0.0;
  double confidence_y = 0.0;
  int evaluations = 0;  // distinct distance evaluations
  std::int64_t pixels_compared = 0;
};

// Finds where a reference patch lies in the current frame. Implementations are stateless
// and may be shared between threads.
class SearchStrategy {
 public:
  virtual ~SearchStrategy() = default;
  virtual std::string name() const = 0;
  virtual SearchResult Search(const ReferencePatch& reference, const cv::Mat& current,
                              const SearchOptions& options) const = 0;
};

// "all", "h23", "h21", "h19", "h17", "h15" or "pyr" (SearchStrategyNames()); nullptr and a
// reason otherwise.
std::unique_ptr<SearchStrategy> MakeSearchStrategy(std::string_view name, std::string* error);

}  // namespace kapfix
