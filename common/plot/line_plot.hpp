#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace kapfix::plot {

struct PlotSeries {
  std::string label;
  std::vector<double> y;  // plotted against its index
  cv::Scalar color{200, 80, 20};
};

// A plain line chart rendered with OpenCV (no GUI toolkit on the analysis side): axes with
// min/max labels, a title and a legend. Non-finite samples are skipped.
cv::Mat RenderLinePlot(const std::string& title, const std::string& x_label,
                       const std::string& y_label, const std::vector<PlotSeries>& series,
                       cv::Size size = {900, 420});

// The same for a set of small charts side by side (small multiples, e.g. one per slice),
// sharing the y range so that they compare at a glance.
cv::Mat RenderSmallMultiples(const std::string& title, const std::vector<PlotSeries>& panels,
                             int columns = 3, cv::Size panel = {300, 160});

}  // namespace kapfix::plot
