#include "common/plot/heat_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace kapfix::plot {
namespace {

constexpr int kCellW = 78, kCellH = 26;         // [px]
constexpr int kRowLabelW = 130, kHeaderH = 90;  // [px]
constexpr double kFont = 0.4;
constexpr int kLabelLines = 3;  // header lines a column label may take

int TextWidth(const std::string& text) {
  int baseline = 0;
  return cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, kFont, 1, &baseline).width;
}

// A column label in lines that each fit a cell, broken after a '/', '_', '.' or ' ' where one
// is near, else at the last character that fits; what still does not fit after kLabelLines
// lines is cut with "..".
std::vector<std::string> ColumnLabelLines(const std::string& label) {
  const int width = kCellW - 4;
  std::vector<std::string> lines;
  std::string rest = label;
  while (!rest.empty() && static_cast<int>(lines.size()) < kLabelLines) {
    std::size_t fit = rest.size();
    while (fit > 1 && TextWidth(rest.substr(0, fit)) > width) --fit;
    if (fit < rest.size()) {
      const std::size_t brk = rest.find_last_of("/_. ", fit - 1);
      if (brk != std::string::npos && brk + 1 >= fit / 2) fit = brk + 1;
    }
    lines.push_back(rest.substr(0, fit));
    rest.erase(0, fit);
  }
  if (!rest.empty()) {
    std::string& last = lines.back();
    while (last.size() > 1 && TextWidth(last + "..") > width) last.pop_back();
    last += "..";
  }
  return lines;
}

}  // namespace

cv::Mat RenderHeatMap(const std::string& title, const std::vector<std::string>& row_labels,
                      const std::vector<std::string>& column_labels,
                      const std::vector<double>& values, double low, double high) {
  const std::size_t rows = row_labels.size(), cols = column_labels.size();
  if (values.size() != rows * cols) {
    throw std::invalid_argument("RenderHeatMap: values must be rows × columns");
  }
  if (!(low > 0 && high > low)) throw std::invalid_argument("RenderHeatMap: need 0 < low < high");
  int baseline = 0;
  const int title_w = cv::getTextSize(title, cv::FONT_HERSHEY_SIMPLEX, 0.55, 1, &baseline).width;
  cv::Mat canvas(kHeaderH + static_cast<int>(rows) * kCellH + 10,
                 std::max(kRowLabelW + static_cast<int>(cols) * kCellW + 10, title_w + 20), CV_8UC3,
                 cv::Scalar(255, 255, 255));
  cv::putText(canvas, title, {10, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  // The scale, one byte per cell, coloured once through VIRIDIS.
  cv::Mat shade(1, static_cast<int>(rows * cols), CV_8UC1);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double v = std::clamp(values[i], low, high);
    const double t = std::isfinite(values[i]) ? std::log(v / low) / std::log(high / low) : 0.0;
    shade.at<std::uint8_t>(0, static_cast<int>(i)) =
        static_cast<std::uint8_t>(std::lround(255 * t));
  }
  cv::Mat colour;
  cv::applyColorMap(shade, colour, cv::COLORMAP_VIRIDIS);
  for (std::size_t c = 0; c < cols; ++c) {
    // Column labels at an angle would need a rotated text: wrapped to the cell's width instead,
    // bottom-aligned above the grid.
    const std::vector<std::string> lines = ColumnLabelLines(column_labels[c]);
    const int x = kRowLabelW + static_cast<int>(c) * kCellW + 2;
    for (std::size_t l = 0; l < lines.size(); ++l) {
      const int y = kHeaderH - 8 - static_cast<int>(lines.size() - 1 - l) * 16;
      cv::putText(canvas, lines[l], {x, y}, cv::FONT_HERSHEY_SIMPLEX, kFont, cv::Scalar(0, 0, 0), 1,
                  cv::LINE_AA);
    }
  }
  for (std::size_t r = 0; r < rows; ++r) {
    const int y = kHeaderH + static_cast<int>(r) * kCellH;
    cv::putText(canvas, row_labels[r], {4, y + 17}, cv::FONT_HERSHEY_SIMPLEX, kFont,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    for (std::size_t c = 0; c < cols; ++c) {
      const std::size_t i = r * cols + c;
      const cv::Rect cell(kRowLabelW + static_cast<int>(c) * kCellW, y, kCellW - 2, kCellH - 2);
      const bool finite = std::isfinite(values[i]);
      const cv::Vec3b bgr = colour.at<cv::Vec3b>(0, static_cast<int>(i));
      const cv::Scalar fill =
          finite ? cv::Scalar(bgr[0], bgr[1], bgr[2]) : cv::Scalar(180, 180, 180);
      cv::rectangle(canvas, cell, fill, cv::FILLED);
      char text[32];
      std::snprintf(text, sizeof text, finite ? "%.1f" : "-", values[i]);
      const bool bright = finite && shade.at<std::uint8_t>(0, static_cast<int>(i)) > 150;
      cv::putText(canvas, text, {cell.x + 6, cell.y + 17}, cv::FONT_HERSHEY_SIMPLEX, kFont,
                  bright ? cv::Scalar(0, 0, 0) : cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
    }
  }
  return canvas;
}

}  // namespace kapfix::plot
