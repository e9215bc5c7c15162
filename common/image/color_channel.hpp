#pragma once

#include <opencv2/core.hpp>
#include <optional>
#include <string_view>

namespace kapfix {

// Which colour information the distance is computed on (SPEC §2.1). The thesis settled on
// green; its rgb alternative is the per-channel SSD, Σ (ΔB² + ΔG² + ΔR²) over the sampled
// pixels (kRgb). The SSD of the sum B + G + R (kRgbSum) is cheaper but blind to hue: it scores
// (255, 0, 0) against (0, 255, 0) as equal.
enum class ColorChannel {
  kGreen,   // "green":   CV_8UC1, the green plane of a BGR frame
  kRgbSum,  // "rgb-sum": CV_16UC1, B + G + R per pixel [0, 765]
  kRgb,     // "rgb":     CV_8UC3, the BGR frame itself; ReferencePatch sums the channels' SSDs
};

// Converts a BGR (CV_8UC3) or grey (CV_8UC1) frame into the plane the matcher reads. A grey
// input is returned as it is for kGreen, tripled for kRgbSum and copied into all three
// channels for kRgb, so that every channel of a grey scene carries the same information.
cv::Mat ExtractChannel(const cv::Mat& frame, ColorChannel channel);

// "green", "rgb" or "rgb-sum".
std::optional<ColorChannel> ParseColorChannel(std::string_view text);
std::string_view ToString(ColorChannel channel);

}  // namespace kapfix
