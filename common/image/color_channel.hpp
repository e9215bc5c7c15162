#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string_view>

namespace kapfix {

// Which colour information the distance is computed on (SPEC §2.1). The thesis settled on
// green; the sum of the three channels is offered for scenes where green is flat.
enum class ColorChannel {
  kGreen,   // CV_8UC1, the green plane of a BGR frame
  kRgbSum,  // CV_16UC1, B + G + R per pixel [0, 765]
};

// Converts a BGR (CV_8UC3) or grey (CV_8UC1) frame into the single plane the matcher reads.
// A grey input is returned as it is for kGreen and tripled for kRgbSum so that both channels
// of a grey scene carry the same information.
cv::Mat ExtractChannel(const cv::Mat& frame, ColorChannel channel);

std::optional<ColorChannel> ParseColorChannel(std::string_view text);
std::string_view ToString(ColorChannel channel);

}  // namespace kapfix
