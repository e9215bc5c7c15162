#include "bench/peer_matchers.hpp"

#include <any>
#include <opencv2/imgproc.hpp>

namespace kapfix::bench {

SearchResult MatchTemplatePeer::Search(const ReferencePatch& reference, const cv::Mat& current,
                                       const SearchOptions& /*options*/) const {
  const cv::Rect box = reference.samples().bounds();
  cv::Mat scores;
  cv::matchTemplate(current, reference.image()(box), scores, cv::TM_SQDIFF);
  double lowest = 0;
  cv::Point at;
  cv::minMaxLoc(scores, &lowest, nullptr, &at, nullptr);
  SearchResult result;
  result.found = true;
  result.shift = at - box.tl();
  result.displacement = result.shift;
  result.distance = static_cast<std::int64_t>(lowest);
  result.evaluations = scores.rows * scores.cols;
  result.pixels_compared = static_cast<std::int64_t>(result.evaluations) * box.area();
  return result;
}

SearchResult PhaseCorrelatePeer::Search(const ReferencePatch& reference, const cv::Mat& current,
                                        const SearchOptions& /*options*/) const {
  struct Windowed {
    cv::Mat window;
    cv::Mat reference;
  };
  const auto& derived = reference.Derived("phase-correlate", [&] {
    Windowed w;
    cv::createHanningWindow(w.window, reference.image().size(), CV_64F);
    cv::Mat as_float;
    reference.image().convertTo(as_float, CV_64F);
    w.reference = as_float.mul(w.window);
    return std::any(w);
  });
  const auto& windowed = std::any_cast<const Windowed&>(derived);
  const cv::Mat& windowed_reference = windowed.reference;
  const cv::Mat& window = windowed.window;
  cv::Mat windowed_current;
  current.convertTo(windowed_current, CV_64F);
  windowed_current = windowed_current.mul(window);
  double response = 0;
  const cv::Point2d shift =
      cv::phaseCorrelate(windowed_reference, windowed_current, cv::noArray(), &response);
  SearchResult result;
  result.found = true;
  result.displacement = shift;
  result.shift = {static_cast<int>(std::lround(shift.x)), static_cast<int>(std::lround(shift.y))};
  result.confidence = result.confidence_x = result.confidence_y = response;
  result.evaluations = 1;
  result.pixels_compared = current.total();
  return result;
}

}  // namespace kapfix::bench
