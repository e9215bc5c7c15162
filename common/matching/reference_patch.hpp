#pragma once

#include <any>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "common/sampling/sample_set.hpp"

namespace kapfix {

// A stored reference: the sampled pixels' values of one plane (CV_8UC1, CV_16UC1 or CV_8UC3, see
// ExtractChannel) and where they sit. Distance() is the SSD between those values and the
// pixels under them in a current plane moved by a shift (SPEC §1 "displacement": the patch is
// found at reference position + shift). On a CV_8UC3 plane it is the thesis's per-channel SSD,
// Σ (ΔB² + ΔG² + ΔR²) over the sampled pixels.
//
// Edge handling (SPEC §2.1): a shift that would move any sampled pixel out of the current
// frame is not scored at all; ShiftRange()/CanShift() clamp the search range so that every
// scored shift compares the same number of pixels, and distances stay comparable.
class ReferencePatch {
 public:
  ReferencePatch() = default;
  ReferencePatch(const cv::Mat& reference, SampleSet samples);

  // SSD at `shift`. Requires CanShift(current.size(), shift) and current.type() == type().
  std::int64_t Distance(const cv::Mat& current, cv::Point shift) const;

  bool CanShift(cv::Size frame, cv::Point shift) const;
  // Inclusive range [first, last] of shifts along x (or y) that keep every sampled pixel
  // inside `frame`, intersected with [−range, +range]; empty (first > last) if none.
  struct ShiftInterval {
    int first = 0;
    int last = -1;
    bool empty() const { return first > last; }
    bool contains(int s) const { return s >= first && s <= last; }
  };
  ShiftInterval ShiftRangeX(cv::Size frame, int range) const;
  ShiftInterval ShiftRangeY(cv::Size frame, int range) const;

  const SampleSet& samples() const { return samples_; }
  // The plane the reference values were read from (shared, not copied).
  const cv::Mat& image() const { return image_; }
  int type() const { return image_.type(); }
  int size() const { return samples_.size(); }
  bool empty() const { return samples_.empty(); }

  // Data a search strategy derives from this reference once and reuses for every search
  // against it (pyr's reduced reference, say). Built by `make` on first use under `key`;
  // thread-safe. The reference is immutable, so what is derived from it never goes stale;
  // copies of a ReferencePatch share the cache.
  const std::any& Derived(const std::string& key, const std::function<std::any()>& make) const;

 private:
  struct DerivedCache {
    std::mutex mutex;
    std::vector<std::pair<std::string, std::any>> entries;
  };

  template <typename T>
  std::int64_t DistanceImpl(const cv::Mat& current, cv::Point shift) const;
  // CV_8UC3: kept apart so that the single-channel path above stays as it was.
  std::int64_t DistanceBgr(const cv::Mat& current, cv::Point shift) const;

  cv::Mat image_;
  SampleSet samples_;
  std::vector<std::uint8_t> values8_;    // CV_8UC1 (CV_8UC3: B, G, R interleaved) reference, in
                                         // SampleSet::Points() order
  std::vector<std::uint16_t> values16_;  // CV_16UC1 reference
  // In elements: on a CV_8UC3 plane a pixel is 3 elements, a span 3 · length of them and a
  // single three offsets (B, G, R), so that the 8-bit kernels run on it unchanged.
  std::vector<std::int32_t> span_offsets_;  // y · step + x · channels of each span's first pixel
  std::vector<std::int32_t> span_lengths_;
  std::vector<std::int32_t> single_offsets_;  // y · step + x · channels (+ c) of each single
  std::size_t offsets_step_ = 0;              // the step (elements) the offsets assume
  std::shared_ptr<DerivedCache> derived_ = std::make_shared<DerivedCache>();
};

}  // namespace kapfix
