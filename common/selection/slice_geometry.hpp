#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace kapfix {

// Where the square patch of a slice sits (SPEC §1 "slice"): the frame is cut into
// `slice_count` equal horizontal bands, numbered 1 = top … slice_count = bottom; the patch is
// centred horizontally and on the band's vertical centre (top = floor(centre − size / 2)), then
// moved vertically just enough to lie inside the frame — a 100-px patch is taller than a
// 33-px slice of a 300-px frame, so the outer slices' patches overlap their neighbours (with 9
// slices of 300 px, slices 1 and 2 share the top patch). [px]
//
// Throws std::invalid_argument for an empty frame, slice_count outside 1 … frame height,
// slice_index outside 1 … slice_count, or a patch_size outside 1 … min(width, height).
cv::Rect SlicePatch(cv::Size frame, int slice_count, int slice_index, int patch_size);

// The slices grouped by the patch they get: a group of several slices shares one patch
// (outer slices clamped into a frame shorter than UnclampedSliceHeight), a group of one has a
// patch of its own. Groups in slice order, indices ascending. Counting a shared patch once is
// what keeps a correlation over slices honest (slices 1 and 2 of a 300-px frame are one
// measurement, not two). Same preconditions as SlicePatch.
std::vector<std::vector<int>> SliceGroups(cv::Size frame, int slice_count, int patch_size);

// [px] The least frame height at which every slice's patch is centred on its own band, none
// clamped: slice_count · patch_size (the thesis's long vertical strip cut into 9 parts).
int UnclampedSliceHeight(int slice_count, int patch_size);

}  // namespace kapfix
