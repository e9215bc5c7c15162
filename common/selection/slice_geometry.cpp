#include "common/selection/slice_geometry.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace kapfix {

cv::Rect SlicePatch(cv::Size frame, int slice_count, int slice_index, int patch_size) {
  if (frame.width <= 0 || frame.height <= 0) {
    throw std::invalid_argument("SlicePatch: empty frame " + std::to_string(frame.width) + "×" +
                                std::to_string(frame.height));
  }
  if (slice_count < 1 || slice_count > frame.height) {
    throw std::invalid_argument("SlicePatch: slice count must be 1…" +
                                std::to_string(frame.height) + " (the frame height), got " +
                                std::to_string(slice_count));
  }
  if (slice_index < 1 || slice_index > slice_count) {
    throw std::invalid_argument("SlicePatch: slice index must be 1…" + std::to_string(slice_count) +
                                " (1 = top), got " + std::to_string(slice_index));
  }
  if (patch_size < 1 || patch_size > std::min(frame.width, frame.height)) {
    throw std::invalid_argument("SlicePatch: patch size " + std::to_string(patch_size) +
                                " px does not fit the " + std::to_string(frame.width) + "×" +
                                std::to_string(frame.height) + " frame");
  }
  // Slice i spans [(i − 1)·H/N, i·H/N); its centre is (2i − 1)·H/(2N). In integers, so that
  // the central slice of an odd N gives exactly MakePatchLayout's central patch.
  const long long numerator =
      (2LL * slice_index - 1) * frame.height - static_cast<long long>(slice_count) * patch_size;
  const long long denominator = 2LL * slice_count;
  long long top = numerator / denominator;
  if (numerator % denominator != 0 && numerator < 0) --top;  // floor, not truncation
  top = std::clamp<long long>(top, 0, frame.height - patch_size);
  return {(frame.width - patch_size) / 2, static_cast<int>(top), patch_size, patch_size};
}

std::vector<std::vector<int>> SliceGroups(cv::Size frame, int slice_count, int patch_size) {
  std::vector<std::vector<int>> groups;
  cv::Rect previous;
  for (int i = 1; i <= slice_count; ++i) {
    const cv::Rect patch = SlicePatch(frame, slice_count, i, patch_size);
    // Patches move down monotonically with the index, so equal ones are neighbours.
    if (!groups.empty() && patch == previous) {
      groups.back().push_back(i);
    } else {
      groups.push_back({i});
    }
    previous = patch;
  }
  return groups;
}

int UnclampedSliceHeight(int slice_count, int patch_size) { return slice_count * patch_size; }

}  // namespace kapfix
