#include "common/search/pyramid_search.hpp"

#include <algorithm>
#include <cstdlib>
#include <map>
#include <opencv2/imgproc.hpp>

#include "common/matching/ssd_kernel.hpp"
#include "common/search/axis_probe.hpp"
#include "common/search/match_confidence.hpp"

namespace kapfix {
namespace {

constexpr int kFineWindow = 2;  // [level pixels] re-scored around the coarser level's best
constexpr int kBlurMargin = 4;  // [px] context kept around crops for pyrDown's kernel

int FloorTo(int v, int step) { return v >= 0 ? v / step * step : -((-v + step - 1) / step) * step; }

// A crop of a plane on a grid aligned to `step`, reduced `levels` times.
struct Crop {
  cv::Point origin;              // [px] top-left of the crop in frame coordinates
  std::vector<cv::Mat> pyramid;  // level 0 = full resolution
};

Crop MakeCrop(const cv::Mat& plane, cv::Rect want, int levels) {
  const int step = 1 << levels;
  const cv::Rect frame(0, 0, plane.cols, plane.rows);
  cv::Rect r = want & frame;
  // Align the top-left to the grid (inside the frame), the size to whole coarse pixels.
  const int x0 = std::max(0, FloorTo(r.x, step));
  const int y0 = std::max(0, FloorTo(r.y, step));
  int w = FloorTo(r.br().x - x0, step);
  int h = FloorTo(r.br().y - y0, step);
  w = std::max(w, step);
  h = std::max(h, step);
  if (x0 + w > plane.cols) w = FloorTo(plane.cols - x0, step);
  if (y0 + h > plane.rows) h = FloorTo(plane.rows - y0, step);
  Crop crop;
  crop.origin = {x0, y0};
  crop.pyramid.push_back(plane(cv::Rect(x0, y0, w, h)).clone());
  for (int l = 1; l <= levels; ++l) {
    cv::Mat down;
    cv::pyrDown(crop.pyramid.back(), down);
    crop.pyramid.push_back(down);
  }
  return crop;
}

// SSD of a dense rectangle of `a` against the same-sized rectangle of `b` at `b_tl`.
template <typename T>
std::int64_t DenseSsd(const cv::Mat& a, cv::Rect a_rect, const cv::Mat& b, cv::Point b_tl) {
  std::int64_t sum = 0;
  for (int y = 0; y < a_rect.height; ++y) {
    sum += SsdRun(a.ptr<T>(a_rect.y + y) + a_rect.x, b.ptr<T>(b_tl.y + y) + b_tl.x,
                  a_rect.width);
  }
  return sum;
}

template <typename T>
bool SearchOneAxis(const ReferencePatch& reference, const cv::Mat& current, bool along_x,
                   cv::Point centre, int range, int levels, bool subpixel, int* best_out,
                   double* refined_out, double* confidence_out, int* evaluations,
                   std::int64_t* pixels) {
  const int step = 1 << levels;
  const cv::Rect bounds = reference.samples().bounds();
  const cv::Rect ref_want(bounds.x - kBlurMargin, bounds.y - kBlurMargin,
                          bounds.width + 2 * kBlurMargin, bounds.height + 2 * kBlurMargin);
  const cv::Point reach = along_x ? cv::Point(range + std::abs(centre.x), std::abs(centre.y))
                                  : cv::Point(std::abs(centre.x), range + std::abs(centre.y));
  const cv::Rect cur_want(ref_want.x - reach.x, ref_want.y - reach.y,
                          ref_want.width + 2 * reach.x, ref_want.height + 2 * reach.y);
  const Crop ref = MakeCrop(reference.image(), ref_want, levels);
  const Crop cur = MakeCrop(current, cur_want, levels);

  // Coarsest level: the patch (bounds, shrunk to whole coarse pixels) searched exhaustively.
  const cv::Mat& ref_c = ref.pyramid[levels];
  const cv::Mat& cur_c = cur.pyramid[levels];
  const cv::Rect patch_c((bounds.x - ref.origin.x + step - 1) / step,
                         (bounds.y - ref.origin.y + step - 1) / step, bounds.width / step,
                         bounds.height / step);
  if (patch_c.width <= 0 || patch_c.height <= 0 ||
      (patch_c & cv::Rect(0, 0, ref_c.cols, ref_c.rows)) != patch_c) {
    return false;
  }
  // Frame position of the patch at level l and shift s (in level-l pixels) along the axis,
  // expressed in the current crop's level-l coordinates.
  const cv::Point base_c = patch_c.tl() + (ref.origin - cur.origin) / step;
  const cv::Point centre_c(FloorTo(centre.x, step) / step, FloorTo(centre.y, step) / step);
  const cv::Point unit = along_x ? cv::Point(1, 0) : cv::Point(0, 1);
  const cv::Point other_c = along_x ? cv::Point(0, centre_c.y) : cv::Point(centre_c.x, 0);
  const int c_axis = along_x ? centre_c.x : centre_c.y;
  const int range_c = (range + step - 1) / step;
  const cv::Rect cur_c_rect(0, 0, cur_c.cols, cur_c.rows);
  std::map<int, std::int64_t> coarse;
  for (int s = c_axis - range_c; s <= c_axis + range_c; ++s) {
    const cv::Point tl = base_c + other_c + unit * s;
    if ((cv::Rect(tl, patch_c.size()) & cur_c_rect) != cv::Rect(tl, patch_c.size())) continue;
    coarse[s] = DenseSsd<T>(ref_c, patch_c, cur_c, tl);
  }
  if (coarse.empty()) return false;
  *evaluations += static_cast<int>(coarse.size());
  *pixels += static_cast<std::int64_t>(coarse.size()) * patch_c.area();
  *confidence_out = MatchConfidence(coarse, kFineWindow);
  int best = std::min_element(coarse.begin(), coarse.end(), [](const auto& a, const auto& b) {
               return a.second < b.second;
             })->first;

  // Intermediate levels: ±kFineWindow around twice the coarser best, all pixels.
  for (int l = levels - 1; l >= 1; --l) {
    const int f = 1 << l;
    const cv::Mat& ref_l = ref.pyramid[l];
    const cv::Mat& cur_l = cur.pyramid[l];
    const cv::Rect patch_l((bounds.x - ref.origin.x + f - 1) / f,
                           (bounds.y - ref.origin.y + f - 1) / f, bounds.width / f,
                           bounds.height / f);
    const cv::Point base_l = patch_l.tl() + (ref.origin - cur.origin) / f;
    const cv::Point other_l = along_x ? cv::Point(0, FloorTo(centre.y, f) / f)
                                      : cv::Point(FloorTo(centre.x, f) / f, 0);
    const cv::Rect cur_l_rect(0, 0, cur_l.cols, cur_l.rows);
    std::int64_t best_distance = -1;
    int level_best = 2 * best;
    for (int s = 2 * best - kFineWindow; s <= 2 * best + kFineWindow; ++s) {
      const cv::Rect at(base_l + other_l + unit * s, patch_l.size());
      if ((at & cur_l_rect) != at) continue;
      const std::int64_t d = DenseSsd<T>(ref_l, patch_l, cur_l, at.tl());
      ++*evaluations;
      *pixels += patch_l.area();
      if (best_distance < 0 || d < best_distance) {
        best_distance = d;
        level_best = s;
      }
    }
    best = level_best;
  }

  // Full resolution: sampled pixels, ±kFineWindow, then the sub-pixel parabola.
  AxisProbe probe(reference, current, along_x, along_x ? cv::Point(2 * best, centre.y)
                                                       : cv::Point(centre.x, 2 * best),
                  kFineWindow + 1);
  std::int64_t d = 0;
  for (int s = 2 * best - kFineWindow; s <= 2 * best + kFineWindow; ++s) probe.Evaluate(s, &d);
  int fine = 0;
  if (!probe.Best(&fine, &d)) return false;
  *refined_out = subpixel ? probe.Refine(&fine) : fine;
  *best_out = fine;
  *evaluations += probe.evaluations();
  *pixels += static_cast<std::int64_t>(probe.evaluations()) * reference.size();
  return true;
}

}  // namespace

SearchResult PyramidSearch::Search(const ReferencePatch& reference, const cv::Mat& current,
                                   const SearchOptions& options) const {
  SearchResult result;
  cv::Point shift = options.origin;
  cv::Point2d refined(shift);
  double confidence = 1.0;
  for (const bool along_x : {true, false}) {
    if (along_x ? options.axis == SearchAxis::kY : options.axis == SearchAxis::kX) continue;
    int best = 0;
    double sub = 0.0;
    double axis_confidence = 0.0;
    const bool ok =
        reference.type() == CV_8UC1
            ? SearchOneAxis<std::uint8_t>(reference, current, along_x, shift, options.range,
                                          levels_, options.subpixel, &best, &sub,
                                          &axis_confidence, &result.evaluations,
                                          &result.pixels_compared)
            : SearchOneAxis<std::uint16_t>(reference, current, along_x, shift, options.range,
                                           levels_, options.subpixel, &best, &sub,
                                           &axis_confidence, &result.evaluations,
                                           &result.pixels_compared);
    if (!ok) return result;
    (along_x ? shift.x : shift.y) = best;
    (along_x ? refined.x : refined.y) = sub;
    confidence = std::min(confidence, axis_confidence);
  }
  result.found = true;
  result.shift = shift;
  result.displacement = refined;
  result.distance = reference.Distance(current, shift);
  result.confidence = confidence;
  return result;
}

}  // namespace kapfix
