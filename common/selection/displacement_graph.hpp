#pragma once

#include <functional>
#include <opencv2/core.hpp>
#include <vector>

#include "common/sampling/sample_set.hpp"
#include "common/sampling/sampling_pattern.hpp"
#include "common/search/search_strategy.hpp"

namespace kapfix {

// Displacement per frame over a free swing (SPEC §1, §2.4): each frame compared with the one
// before it, so the graph is the swing's frame-to-frame motion, not its position.
struct DisplacementGraph {
  // [px] samples[t − 1] = displacement of frame t against frame t − 1, t = 1 … T (T + 1
  // frames give T samples), along the search axis.
  std::vector<double> samples;
};

// One sample of the graph: the pixels `samples` of `previous` searched for in `current` with
// `strategy`. The value is the displacement along the search axis [px] (kBoth reports x, the
// kite's swing axis), with its sub-pixel part when options.subpixel is set; 0 when the
// strategy finds nothing, so that a lost frame reads as "no motion" rather than a spike.
double MeasureDisplacement(const cv::Mat& previous, const cv::Mat& current,
                           const SampleSet& samples, const SearchStrategy& strategy,
                           const SearchOptions& options);

// The graph of `patch` (frame coordinates, sampled by `sampling`) over planes
// (CV_8UC1, CV_16UC1 or CV_8UC3, see ExtractChannel) of equal size and type. progress(done, total)
// is called after each sample, total = planes.size() − 1. Throws std::invalid_argument on
// mismatched planes, invalid options or a patch outside the frame.
DisplacementGraph BuildDisplacementGraph(const std::vector<cv::Mat>& planes, cv::Rect patch,
                                         const SamplingOptions& sampling,
                                         const SearchStrategy& strategy,
                                         const SearchOptions& options,
                                         const std::function<void(int, int)>& progress = nullptr);

// Throws std::invalid_argument unless every plane is a non-empty CV_8UC1, CV_16UC1 or CV_8UC3 of
// the first plane's size and type (`who` names the caller in the message).
void CheckSwingPlanes(const std::vector<cv::Mat>& planes, const char* who);

}  // namespace kapfix
