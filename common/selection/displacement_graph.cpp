#include "common/selection/displacement_graph.hpp"

#include <stdexcept>
#include <string>

#include "common/matching/reference_patch.hpp"

namespace kapfix {

void CheckSwingPlanes(const std::vector<cv::Mat>& planes, const char* who) {
  for (std::size_t i = 0; i < planes.size(); ++i) {
    const cv::Mat& plane = planes[i];
    if (plane.empty() ||
        (plane.type() != CV_8UC1 && plane.type() != CV_16UC1 && plane.type() != CV_8UC3)) {
      throw std::invalid_argument(
          std::string(who) + ": frame " + std::to_string(i) +
          " is not a CV_8UC1, CV_16UC1 or CV_8UC3 plane (see ExtractChannel)");
    }
    if (plane.size() != planes.front().size() || plane.type() != planes.front().type()) {
      throw std::invalid_argument(std::string(who) + ": frame " + std::to_string(i) +
                                  " differs in size or type from frame 0");
    }
  }
}

double MeasureDisplacement(const cv::Mat& previous, const cv::Mat& current,
                           const SampleSet& samples, const SearchStrategy& strategy,
                           const SearchOptions& options) {
  const ReferencePatch reference(previous, samples);
  const SearchResult result = strategy.Search(reference, current, options);
  if (!result.found) return 0.0;
  const cv::Point2d d = options.subpixel ? result.displacement : cv::Point2d(result.shift);
  return options.axis == SearchAxis::kY ? d.y : d.x;
}

DisplacementGraph BuildDisplacementGraph(const std::vector<cv::Mat>& planes, cv::Rect patch,
                                         const SamplingOptions& sampling,
                                         const SearchStrategy& strategy,
                                         const SearchOptions& options,
                                         const std::function<void(int, int)>& progress) {
  std::string error;
  if (!sampling.IsValid(&error) || !options.IsValid(&error)) {
    throw std::invalid_argument("BuildDisplacementGraph: " + error);
  }
  CheckSwingPlanes(planes, "BuildDisplacementGraph");
  DisplacementGraph graph;
  if (planes.size() < 2) return graph;
  const cv::Rect frame(cv::Point(0, 0), planes.front().size());
  if ((patch & frame) != patch || patch.empty()) {
    throw std::invalid_argument("BuildDisplacementGraph: patch lies outside the frame");
  }
  // The patch sits at the same place in every frame, so its sampled pixels are chosen once.
  const SampleSet samples({patch}, sampling);
  const int total = static_cast<int>(planes.size()) - 1;
  graph.samples.reserve(static_cast<std::size_t>(total));
  for (int t = 1; t <= total; ++t) {
    graph.samples.push_back(
        MeasureDisplacement(planes[t - 1], planes[t], samples, strategy, options));
    if (progress) progress(t, total);
  }
  return graph;
}

}  // namespace kapfix
