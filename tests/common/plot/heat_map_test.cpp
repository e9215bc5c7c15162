#include "common/plot/heat_map.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

namespace kapfix::plot {
namespace {

constexpr int kBelowTitle = 28;  // [px]

// The x range [first, last] of the black ink below the title (the labels; a grey no-value cell
// is not ink); first > last when there is none.
std::pair<int, int> InkColumns(const cv::Mat& canvas) {
  cv::Mat grey;
  cv::cvtColor(canvas.rowRange(kBelowTitle, canvas.rows), grey, cv::COLOR_BGR2GRAY);
  int first = grey.cols, last = -1;
  for (int x = 0; x < grey.cols; ++x) {
    double lowest = 255;
    cv::minMaxLoc(grey.col(x), &lowest);
    if (lowest < 100) {
      first = std::min(first, x);
      last = x;
    }
  }
  return {first, last};
}

// One unlabelled row of grey no-value cells under the given column labels.
cv::Mat LabelsOnly(const std::vector<std::string>& column_labels) {
  const double none = std::numeric_limits<double>::quiet_NaN();
  return RenderHeatMap("t", {""}, column_labels, std::vector<double>(column_labels.size(), none),
                       1.0, 10.0);
}

TEST(HeatMapTest, NeighbouringColumnLabelsDoNotOverlap) {
  // The loop benchmark's world/start labels: "nominal/ssp" ran into the next column's label.
  const auto left = InkColumns(LabelsOnly({"nominal/ssp", ""}));
  const auto right = InkColumns(LabelsOnly({"", "realistic/ssp"}));
  ASSERT_LE(left.first, left.second);
  ASSERT_LE(right.first, right.second);
  // At least a space's width [px] between them, or the two read as one word.
  EXPECT_GE(right.first - left.second, 4);
}

TEST(HeatMapTest, ALabelTooLongForThreeLinesStaysInItsColumn) {
  const std::string label(60, 'w');
  const auto alone = InkColumns(LabelsOnly({label, ""}));
  const auto next = InkColumns(LabelsOnly({"", "x"}));
  ASSERT_LE(alone.first, alone.second);
  EXPECT_LT(alone.second, next.first);
}

}  // namespace
}  // namespace kapfix::plot
