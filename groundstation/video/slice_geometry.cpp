#include "groundstation/video/slice_geometry.hpp"

#include <algorithm>
#include <cmath>

namespace kapfix::station {

unsigned SliceAt(double y_px, double frame_height_px, unsigned slice_count) {
  if (slice_count == 0 || frame_height_px <= 0 || y_px < 0 || y_px >= frame_height_px) return 0;
  const double band = frame_height_px / slice_count;
  const auto index = static_cast<unsigned>(std::floor(y_px / band)) + 1;
  return std::min(index, slice_count);
}

QRectF SliceBand(unsigned index, unsigned slice_count, double frame_width_px,
                 double frame_height_px) {
  if (slice_count == 0 || index == 0 || index > slice_count) return {};
  const double band = frame_height_px / slice_count;
  return {0.0, band * (index - 1), frame_width_px, band};
}

}  // namespace kapfix::station
