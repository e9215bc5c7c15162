#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <string_view>
#include <vector>

namespace kapfix {

// Which pixels of a patch take part in a comparison (SPEC §2.2).
enum class SamplingKind {
  kAll,     // every patch pixel
  kStatic,  // spacing 10, 9, 8 … 1, repeated, in raster order (thesis §3.2.1.5.1)
  kRandom,  // a seeded, uniformly distributed subset (thesis: 10 %)
};

struct SamplingOptions {
  SamplingKind kind = SamplingKind::kRandom;
  double fraction = 0.1;   // kRandom only: share of the patch's pixels, (0, 1]
  std::uint32_t seed = 1;  // kRandom only

  bool IsValid(std::string* error) const;
};

// Parses "all", "static", "random" or "random:F" (F the fraction, e.g. random:0.1).
bool ParseSamplingOptions(std::string_view text, SamplingOptions* options, std::string* error);
std::string ToString(const SamplingOptions& options);

// Offsets (x, y) inside a patch of the given size, in raster order, without repeats.
//
// kStatic walks the patch's pixels in raster order (index = y * width + x) and takes one
// every 10, then 9, … then 1 pixels, and starts over (a cycle of 55 pixels). The gaps differ,
// so under most translations some sampled pixels land on sampled pixels, where a regular
// grid of step n has none under any shift that is not a multiple of n. (The thesis says
// "every" translation; measured on a 100-pixel-wide patch, horizontal shifts of 23 and 32
// find no overlap — the cycle's difference set misses them.) Keeps ~18 % of the pixels.
//
// kRandom draws exactly round(fraction * area) distinct pixels with a partial Fisher–Yates
// shuffle driven by std::mt19937 (whose output sequence the C++ standard fixes), mapping
// its 32-bit outputs to a range by modulo; the pattern is therefore identical on every
// platform and run for the same seed.
std::vector<cv::Point> MakeSamplingPattern(cv::Size patch, const SamplingOptions& options);

}  // namespace kapfix
