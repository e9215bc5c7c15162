#include "common/sampling/patch_layout.hpp"

#include <cmath>
#include <stdexcept>

namespace kapfix {
namespace {

// Scales a rectangle given on the thesis's 300×300 frame to `frame`.
cv::Rect ScaleFrom300(int x, int y, int size, cv::Size frame) {
  const double sx = frame.width / 300.0;
  const double sy = frame.height / 300.0;
  return {static_cast<int>(std::lround(x * sx)), static_cast<int>(std::lround(y * sy)),
          static_cast<int>(std::lround(size * sx)), static_cast<int>(std::lround(size * sy))};
}

}  // namespace

std::vector<cv::Rect> MakePatchLayout(PatchLayout layout, cv::Size frame, int patch_size) {
  if (frame.width <= 0 || frame.height <= 0) throw std::invalid_argument("empty frame");
  switch (layout) {
    case PatchLayout::kCentral: {
      if (patch_size <= 0 || patch_size > frame.width || patch_size > frame.height) {
        throw std::invalid_argument("patch size " + std::to_string(patch_size) +
                                    " does not fit the frame");
      }
      return {cv::Rect((frame.width - patch_size) / 2, (frame.height - patch_size) / 2, patch_size,
                       patch_size)};
    }
    case PatchLayout::kIndividuals:
      return {ScaleFrom300(50, 50, 50, frame), ScaleFrom300(200, 50, 50, frame),
              ScaleFrom300(50, 200, 50, frame), ScaleFrom300(200, 200, 50, frame)};
    case PatchLayout::kMerge:
      return {ScaleFrom300(40, 40, 40, frame), ScaleFrom300(220, 40, 40, frame),
              ScaleFrom300(40, 220, 40, frame), ScaleFrom300(220, 220, 40, frame),
              ScaleFrom300(130, 130, 40, frame)};
  }
  return {};
}

std::optional<PatchLayout> ParsePatchLayout(std::string_view text) {
  if (text == "central") return PatchLayout::kCentral;
  if (text == "individuals") return PatchLayout::kIndividuals;
  if (text == "merge") return PatchLayout::kMerge;
  return std::nullopt;
}

std::string_view ToString(PatchLayout layout) {
  switch (layout) {
    case PatchLayout::kCentral:
      return "central";
    case PatchLayout::kIndividuals:
      return "individuals";
    case PatchLayout::kMerge:
      return "merge";
  }
  return "?";
}

}  // namespace kapfix
