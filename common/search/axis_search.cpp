#include "common/search/axis_search.hpp"

#include <algorithm>

namespace kapfix {

SearchResult AxisSearch::Search(const ReferencePatch& reference, const cv::Mat& current,
                                const SearchOptions& options) const {
  SearchResult result;
  result.confidence_x = result.confidence_y = 1.0;  // until searched
  cv::Point shift = options.origin;
  cv::Point2d refined(shift);
  double confidence = 1.0;
  const bool do_x = options.axis != SearchAxis::kY;
  const bool do_y = options.axis != SearchAxis::kX;
  for (const bool along_x : {true, false}) {
    if ((along_x && !do_x) || (!along_x && !do_y)) continue;
    // The probe itself is bounded by the frame and by twice the range: hierarchical levels
    // may step past ±R around the centre (level 1's −100 plus level 2's −15).
    AxisProbe probe(reference, current, along_x, shift, 2 * options.range);
    SearchAxis(probe, options.range);
    int best = 0;
    std::int64_t distance = 0;
    if (!probe.Best(&best, &distance)) return result;  // nothing could be scored
    const double sub = options.subpixel ? probe.Refine(&best) : best;
    if (options.subpixel) distance = reference.Distance(current, probe.ShiftAt(best));
    (along_x ? shift.x : shift.y) = best;
    (along_x ? refined.x : refined.y) = sub;
    (along_x ? result.confidence_x : result.confidence_y) = probe.Confidence();
    confidence = std::min(confidence, probe.Confidence());
    result.distance = distance;
    result.evaluations += probe.evaluations();
  }
  result.found = true;
  result.shift = shift;
  result.displacement = refined;
  result.confidence = confidence;
  result.pixels_compared = static_cast<std::int64_t>(result.evaluations) * reference.size();
  return result;
}

}  // namespace kapfix
