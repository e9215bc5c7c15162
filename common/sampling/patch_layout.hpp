#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string_view>
#include <vector>

namespace kapfix {

// Where the patches sit for the chapter-3 surface studies (SPEC §2.2, thesis §3.2.1.1).
enum class PatchLayout {
  kCentral,      // one square patch in the centre of the frame
  kIndividuals,  // four 50×50 patches at (50,50), (200,50), (50,200), (200,200) of 300×300
  kMerge,        // five 40×40: four at (40,40) … (220,220) and one in the centre
};

// Rectangles in frame coordinates. The thesis's geometry is given for a 300×300 frame and is
// scaled to other frame sizes; `patch_size` is used by kCentral only.
std::vector<cv::Rect> MakePatchLayout(PatchLayout layout, cv::Size frame, int patch_size);

std::optional<PatchLayout> ParsePatchLayout(std::string_view text);
std::string_view ToString(PatchLayout layout);

}  // namespace kapfix
