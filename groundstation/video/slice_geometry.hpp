#pragma once

// Which slice a point of the frame lies in, and where a slice lies (SPEC §1: N equal
// horizontal bands, numbered 1 = top). Frame pixels throughout.

#include <QRectF>

namespace kapfix::station {

// [1..slice_count] the slice containing row y [px]; 0 when y is outside the frame or there
// are no slices.
unsigned SliceAt(double y_px, double frame_height_px, unsigned slice_count);

// [px] the band of slice `index` (1 = top) in a frame of the given size.
QRectF SliceBand(unsigned index, unsigned slice_count, double frame_width_px,
                 double frame_height_px);

}  // namespace kapfix::station
