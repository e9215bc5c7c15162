#include "common/plot/line_plot.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace kapfix::plot {
namespace {

struct Range {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  std::size_t n = 0;
  void Add(const std::vector<double>& ys) {
    for (const double y : ys) {
      if (!std::isfinite(y)) continue;
      lo = std::min(lo, y);
      hi = std::max(hi, y);
    }
    n = std::max(n, ys.size());
  }
  void Fix() {
    if (!std::isfinite(lo)) lo = hi = 0.0;
    if (hi - lo < 1e-9) {
      lo -= 1.0;
      hi += 1.0;
    }
  }
};

std::string Number(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), std::abs(v) >= 1000 ? "%.3g" : "%.1f", v);
  return text;
}

void DrawSeries(cv::Mat& canvas, cv::Rect area, const Range& range, const PlotSeries& s) {
  cv::Point previous(-1, -1);
  const double xs =
      s.y.size() > 1 ? static_cast<double>(area.width) / static_cast<double>(range.n - 1) : 0.0;
  for (std::size_t i = 0; i < s.y.size(); ++i) {
    if (!std::isfinite(s.y[i])) {
      previous = {-1, -1};
      continue;
    }
    const cv::Point p(area.x + static_cast<int>(std::lround(static_cast<double>(i) * xs)),
                      area.y + area.height -
                          static_cast<int>(std::lround((s.y[i] - range.lo) / (range.hi - range.lo) *
                                                       area.height)));
    if (previous.x >= 0) cv::line(canvas, previous, p, s.color, 1, cv::LINE_AA);
    previous = p;
  }
}

void DrawFrame(cv::Mat& canvas, cv::Rect area, const Range& range, double font) {
  cv::rectangle(canvas, area, cv::Scalar(120, 120, 120));
  if (range.lo < 0 && range.hi > 0) {
    const int zero = area.y + area.height -
                     static_cast<int>(std::lround(-range.lo / (range.hi - range.lo) * area.height));
    cv::line(canvas, {area.x, zero}, {area.br().x, zero}, cv::Scalar(210, 210, 210));
  }
  cv::putText(canvas, Number(range.hi), {2, area.y + 10}, cv::FONT_HERSHEY_SIMPLEX, font,
              cv::Scalar(60, 60, 60));
  cv::putText(canvas, Number(range.lo), {2, area.br().y}, cv::FONT_HERSHEY_SIMPLEX, font,
              cv::Scalar(60, 60, 60));
}

}  // namespace

cv::Mat RenderLinePlot(const std::string& title, const std::string& x_label,
                       const std::string& y_label, const std::vector<PlotSeries>& series,
                       cv::Size size) {
  cv::Mat canvas(size, CV_8UC3, cv::Scalar(255, 255, 255));
  Range range;
  for (const auto& s : series) range.Add(s.y);
  range.Fix();
  const cv::Rect area(70, 40, size.width - 90, size.height - 85);
  DrawFrame(canvas, area, range, 0.45);
  for (const auto& s : series) DrawSeries(canvas, area, range, s);
  cv::putText(canvas, title, {area.x, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  cv::putText(canvas, x_label + " (0.." + std::to_string(range.n > 0 ? range.n - 1 : 0) + ")",
              {area.x, size.height - 15}, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0));
  cv::putText(canvas, y_label, {2, area.y + area.height / 2}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
              cv::Scalar(0, 0, 0));
  int legend_x = area.x + 260;
  for (const auto& s : series) {
    cv::line(canvas, {legend_x, 20}, {legend_x + 20, 20}, s.color, 2);
    cv::putText(canvas, s.label, {legend_x + 25, 25}, cv::FONT_HERSHEY_SIMPLEX, 0.45, s.color, 1,
                cv::LINE_AA);
    legend_x += 40 + static_cast<int>(s.label.size()) * 9;
  }
  return canvas;
}

cv::Mat RenderSmallMultiples(const std::string& title, const std::vector<PlotSeries>& panels,
                             int columns, cv::Size panel) {
  columns = std::max(1, columns);
  const int rows = (static_cast<int>(panels.size()) + columns - 1) / columns;
  cv::Mat canvas(30 + rows * panel.height, columns * panel.width, CV_8UC3,
                 cv::Scalar(255, 255, 255));
  cv::putText(canvas, title, {10, 20}, cv::FONT_HERSHEY_SIMPLEX, 0.6, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  Range range;
  for (const auto& p : panels) range.Add(p.y);
  range.Fix();
  for (std::size_t i = 0; i < panels.size(); ++i) {
    const int c = static_cast<int>(i) % columns;
    const int r = static_cast<int>(i) / columns;
    const cv::Rect area(c * panel.width + 45, 30 + r * panel.height + 20, panel.width - 55,
                        panel.height - 35);
    DrawFrame(canvas, area, range, 0.35);
    DrawSeries(canvas, area, range, panels[i]);
    cv::putText(canvas, panels[i].label, {area.x, area.y - 5}, cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  }
  return canvas;
}

}  // namespace kapfix::plot
