#pragma once

#include <array>
#include <string>
#include <vector>

#include "common/search/axis_search.hpp"

namespace kapfix {

// The offsets of one hierarchical preset at R = 100 (thesis Table 4.5, SPEC §2.3): level 1
// around the search centre, level 2 around level 1's best, level 3 around level 2's best.
struct HierarchicalPreset {
  std::string name;
  std::array<std::vector<int>, 3> levels;

  // Number of offsets visited (the thesis names a preset after it: h23 visits 23).
  int visits() const;
};

// The five presets h23, h21, h19, h17, h15, verbatim.
const std::vector<HierarchicalPreset>& HierarchicalPresets();

// Three-level coarse-to-fine search with a preset's offsets. For R other than 100 every
// offset is scaled by R / 100 (rounded); at R = 100 they are the table's exactly. Offsets
// that fall outside the frame are skipped.
class HierarchicalSearch final : public AxisSearch {
 public:
  explicit HierarchicalSearch(HierarchicalPreset preset);
  std::string name() const override { return preset_.name; }
  const HierarchicalPreset& preset() const { return preset_; }

 protected:
  void SearchAxis(AxisProbe& probe, int range) const override;

 private:
  HierarchicalPreset preset_;
};

}  // namespace kapfix
