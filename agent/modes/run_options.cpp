#include "agent/modes/run_options.hpp"

#include <algorithm>
#include <array>

#include "agent/config/options_from_settings.hpp"

namespace kapfix::agent {
namespace {

constexpr std::array<int, 3> kPatchSizeCandidates{50, 100, 150};  // [px] the thesis's

}  // namespace

ControllerGains MakeGains(const kapfix::v1::Gains& gains) {
  return OptionsFromSettings<ControllerGains>(gains);
}

SearchOptions MakeSearchOptions(const SearchConfig& search) {
  SearchOptions o;
  o.axis = search.axis;
  o.range = search.range_px;
  o.cross_range = std::min(o.cross_range, search.range_px);
  o.subpixel = search.subpixel;
  return o;
}

FixationOptions MakeFixationOptions(const SearchConfig& search, int slice,
                                    FixationOptions::Reference reference) {
  FixationOptions o;
  o.search = MakeSearchOptions(search);
  o.sampling = search.sampling;
  o.channel = search.channel;
  o.patch_size = search.patch_px;
  o.slice_count = search.slices;
  o.slice = slice;
  o.reference = reference;
  return o;
}

SliceSelectionOptions MakeSliceSelectionOptions(const SearchConfig& search) {
  SliceSelectionOptions o;
  o.slice_count = search.slices;
  o.patch_size = search.patch_px;
  o.sampling = search.sampling;
  o.search = MakeSearchOptions(search);
  o.hysteresis_px = search.hysteresis_px;
  o.score = search.score;
  return o;
}

PatchSizeSelectionOptions MakePatchSizeSelectionOptions(const SearchConfig& search,
                                                        cv::Size plane) {
  PatchSizeSelectionOptions o;
  o.sizes.clear();
  for (const int size : kPatchSizeCandidates) {
    if (size <= std::min(plane.width, plane.height)) o.sizes.push_back(size);
  }
  o.sampling = search.sampling;
  o.search = MakeSearchOptions(search);
  return o;
}

bool SameLoop(const AgentConfig& a, const AgentConfig& b) {
  const SearchConfig& s = a.search;
  const SearchConfig& t = b.search;
  const LensProfile& l = a.active_lens();
  const LensProfile& m = b.active_lens();
  return s.strategy == t.strategy && ToString(s.sampling) == ToString(t.sampling) &&
         s.sampling.seed == t.sampling.seed && s.patch_px == t.patch_px && s.slices == t.slices &&
         s.axis == t.axis && s.range_px == t.range_px && s.channel == t.channel &&
         s.subpixel == t.subpixel && s.score == t.score && s.hysteresis_px == t.hysteresis_px &&
         a.gains.controller() == b.gains.controller() && l.name == m.name &&
         l.DegPerPxPan() == m.DegPerPxPan() && l.DegPerPxTilt() == m.DegPerPxTilt();
}

}  // namespace kapfix::agent
