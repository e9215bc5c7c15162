#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace kapfix::plot {

// A table of figures as a coloured grid (e.g. scenes × worlds of a benchmark), rendered with
// OpenCV: each cell coloured by its value on a log scale between `low` (dark) and `high`
// (bright; VIRIDIS) and labelled with the value; non-finite cells grey. `values` is row-major
// rows × columns; a size mismatch throws std::invalid_argument.
cv::Mat RenderHeatMap(const std::string& title, const std::vector<std::string>& row_labels,
                      const std::vector<std::string>& column_labels,
                      const std::vector<double>& values, double low, double high);

}  // namespace kapfix::plot
