#pragma once

#include <atomic>
#include <cstdint>
#include <memory>

#include "common/search/search_strategy.hpp"

namespace kapfix {

// Strategy "pyr" (SPEC §2.3, beyond the thesis): coarse-to-fine over a low-passed pyramid.
//
// The reference patch's neighbourhood and the current frame's search region are cropped on a
// grid aligned to 2^levels pixels and reduced with PyrDown (bit for bit cv::pyrDown: Gaussian
// 5×5, decimation by 2) `levels` times. At the coarsest level every shift of the search window is
// scored over all of the patch's pixels: ±R / 2^levels along the searched axes and ±cross_range /
// 2^levels across a single axis (SearchOptions::cross_range), jointly. Each finer level starts from
// twice the coarser best and descends over 3×3 neighbourhoods (all pixels); full resolution
// does the same with the sampled pixels only, then fits the sub-pixel parabola per searched
// axis. Blur widens the error curve's basin (thesis §3.2.1.3): the coarse level does not lock
// onto a repetitive texture's side valley as h23 does, and tolerates the small cross-axis
// wobble that defeats an X-only search on fine texture. The confidence is the coarse level's
// (MatchConfidence of its window), and 0 when the full-resolution answer ended more than one
// coarse step (2^levels px) from the coarse answer along an axis: the finer levels compare raw
// brightness, and a brightness step pulls their descent off the view.
//
// Cost for R = 100, cross_range = 8, a 100×100 patch, X axis: 51 × 5 coarse shifts of 625
// pixels, about 9 shifts of 2,500 at half resolution and about 9 of the sampled pixels at
// full resolution. With SearchAxis::kBoth the coarse window is 51 × 51 (joint 2-D).
class PyramidSearch final : public SearchStrategy {
 public:
  explicit PyramidSearch(int levels = 2) : levels_(levels) {}
  std::string name() const override { return "pyr"; }
  SearchResult Search(const ReferencePatch& reference, const cv::Mat& current,
                      const SearchOptions& options) const override;
  // How many reduced references this search and its copies built: one per stored reference
  // (shared by the reference's copies), however many searches ran against it.
  std::uint64_t reduced_references_built() const { return built_->load(); }

 private:
  int levels_;
  std::shared_ptr<std::atomic<std::uint64_t>> built_ =
      std::make_shared<std::atomic<std::uint64_t>>(0);
};

}  // namespace kapfix
