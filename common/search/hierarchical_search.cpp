#include "common/search/hierarchical_search.hpp"

#include <cmath>

namespace kapfix {

int HierarchicalPreset::visits() const {
  return static_cast<int>(levels[0].size() + levels[1].size() + levels[2].size());
}

const std::vector<HierarchicalPreset>& HierarchicalPresets() {
  // Thesis Table 4.5. h15's level 2 is one-sided in the thesis; kept as it is (SPEC §2.3).
  static const std::vector<HierarchicalPreset> presets = {
      {"h23",
       {{{-100, -80, -60, -40, -20, 0, 20, 40, 60, 80, 99},
         {-15, -10, -5, 0, 5, 10, 15},
         {-4, -2, 0, 2, 4}}}},
      {"h21",
       {{{-80, -60, -40, -20, 0, 20, 40, 60, 80},
         {-15, -10, -5, 0, 5, 10, 15},
         {-4, -2, 0, 2, 4}}}},
      {"h19",
       {{{-80, -60, -40, -20, 0, 20, 40, 60, 80}, {-15, -10, -5, 0, 5, 10, 15}, {-4, -2, 2}}}},
      {"h17", {{{-75, -50, -25, 0, 25, 50, 74}, {-15, -8, -1, 6, 13}, {-7, -4, -1, 2, 5}}}},
      {"h15", {{{-75, -45, -15, 15, 45, 74}, {-30, -20, -10, 0}, {-6, -3, 0, 3, 6}}}},
  };
  return presets;
}

HierarchicalSearch::HierarchicalSearch(HierarchicalPreset preset) : preset_(std::move(preset)) {}

void HierarchicalSearch::SearchAxis(AxisProbe& probe, int range) const {
  int centre = probe.centre_position();
  std::int64_t distance = 0;
  for (const std::vector<int>& level : preset_.levels) {
    // Only this level's offsets compete for its best (h19's level 3 omits its own centre).
    int level_best = centre;
    std::int64_t level_distance = -1;
    for (const int offset : level) {
      const int scaled =
          range == 100 ? offset : static_cast<int>(std::lround(offset * range / 100.0));
      const int s = centre + scaled;
      if (!probe.Evaluate(s, &distance)) continue;
      if (level_distance < 0 || distance < level_distance) {
        level_distance = distance;
        level_best = s;
      }
    }
    centre = level_best;
  }
}

}  // namespace kapfix
