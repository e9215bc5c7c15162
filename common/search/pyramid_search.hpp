#pragma once

#include "common/search/search_strategy.hpp"

namespace kapfix {

// Strategy "pyr" (SPEC §2.3, beyond the thesis): coarse-to-fine over a low-passed pyramid.
// The reference patch's neighbourhood and the current frame's search strip are cropped on a
// grid aligned to 2^levels pixels and reduced with cv::pyrDown (Gaussian 5×5, then
// decimation). At the coarsest level every shift in ±R / 2^levels is scored over all of the
// patch's pixels; each finer level re-scores the best shift ±2 (over all pixels); the full
// resolution level scores best ± 2 with the sampled pixels only and refines the sub-pixel
// part. Blur widens the error curve's basin (thesis §3.2.1.3), which is what keeps the
// coarse level from locking onto a repetitive texture's side valley as h23 does; the
// confidence is read off the coarse level's complete curve.
class PyramidSearch final : public SearchStrategy {
 public:
  explicit PyramidSearch(int levels = 2) : levels_(levels) {}
  std::string name() const override { return "pyr"; }
  SearchResult Search(const ReferencePatch& reference, const cv::Mat& current,
                      const SearchOptions& options) const override;

 private:
  int levels_;
};

}  // namespace kapfix
