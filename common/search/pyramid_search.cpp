#include "common/search/pyramid_search.hpp"

#include <algorithm>
#include <any>
#include <atomic>
#include <cstdlib>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "common/image/pyramid_filters.hpp"
#include "common/matching/sliding_ssd.hpp"
#include "common/matching/ssd_kernel.hpp"
#include "common/search/match_confidence.hpp"
#include "common/search/subpixel.hpp"

namespace kapfix {
namespace {

constexpr int kBlurMargin = 4;       // [px] context kept around crops for pyrDown's kernel
constexpr int kMaxDescentSteps = 6;  // 3×3 re-centrings per level before giving up

int FloorDiv(int v, int d) { return v >= 0 ? v / d : -((-v + d - 1) / d); }

// Scores of the shifts visited at one level. A handful to a few hundred entries, looked up by
// linear scan: cheaper than a tree's allocations at this size.
class ScoreMap {
 public:
  void reserve(std::size_t n) { entries_.reserve(n); }
  const std::int64_t* find(cv::Point s) const {
    for (const auto& [shift, d] : entries_) {
      if (shift == s) return &d;
    }
    return nullptr;
  }
  void emplace(cv::Point s, std::int64_t d) { entries_.emplace_back(s, d); }
  std::int64_t at(cv::Point s) const { return *find(s); }
  std::size_t size() const { return entries_.size(); }
  bool empty() const { return entries_.empty(); }
  auto begin() const { return entries_.begin(); }
  auto end() const { return entries_.end(); }

 private:
  std::vector<std::pair<cv::Point, std::int64_t>> entries_;
};

// A crop of a plane on a grid aligned to 2^levels, and its reductions.
struct Crop {
  cv::Point origin;              // [px] top-left of the crop in frame coordinates
  std::vector<cv::Mat> pyramid;  // level 0 = full resolution; the coarsest band-passed
  cv::Mat reduced;               // scratch: the coarsest level before its band-pass
};

bool MakeCrop(const cv::Mat& plane, cv::Rect want, int levels, Crop* crop) {
  const int step = 1 << levels;
  const cv::Rect r = want & cv::Rect(0, 0, plane.cols, plane.rows);
  const int x0 = std::max(0, FloorDiv(r.x, step) * step);
  const int y0 = std::max(0, FloorDiv(r.y, step) * step);
  const int w = FloorDiv(std::min(r.br().x, plane.cols) - x0, step) * step;
  const int h = FloorDiv(std::min(r.br().y, plane.rows) - y0, step) * step;
  if (w < step || h < step) return false;
  crop->origin = {x0, y0};
  // A view, not a copy: PyrDown reads the ROI in place.
  // Level buffers are reused from call to call when the crop keeps its size (the current
  // frame's crop is thread-local): no allocation per search.
  crop->pyramid.resize(static_cast<std::size_t>(levels) + 1);
  crop->pyramid[0] = plane(cv::Rect(x0, y0, w, h));
  for (int l = 1; l <= levels; ++l) {
    PyrDown(crop->pyramid[l - 1], l == levels ? crop->reduced : crop->pyramid[l]);
  }
  // The coarsest level is compared band-passed (the level minus its own blur, re-centred on
  // mid grey): smooth shading under a brightness drift otherwise looks like a shift along the
  // shading gradient to SSD and pulls the coarse minimum away by several pixels. Finer levels
  // only refine around it; band-passing them too changed nothing measurable (13 photos).
  BandPass(crop->reduced, crop->pyramid[levels]);
  return true;
}

// The patch's whole pixels at `level` inside its bounds, in the coordinates of a crop whose
// origin is a multiple of 2^level.
cv::Rect LevelPatch(cv::Rect bounds, cv::Point origin, int level) {
  const int f = 1 << level;
  const int x0 = FloorDiv(bounds.x - origin.x + f - 1, f);
  const int y0 = FloorDiv(bounds.y - origin.y + f - 1, f);
  const int x1 = FloorDiv(bounds.br().x - origin.x, f);
  const int y1 = FloorDiv(bounds.br().y - origin.y, f);
  return {x0, y0, x1 - x0, y1 - y0};
}

// What pyr derives from a stored reference once: its reduced crop and, for 8-bit planes, the
// patch at each reduced level prepared for SlidingSsd (index = level; empty at level 0).
struct ReferenceLevels {
  Crop crop;
  std::vector<SlidingSsd> patches;

  const SlidingSsd* patch(int level) const {
    const auto l = static_cast<std::size_t>(level);
    return l < patches.size() && !patches[l].empty() ? &patches[l] : nullptr;
  }
};

// Scores shifts at one reduced level over all of the patch's pixels there. kChannels = 3: a
// BGR plane (ColorChannel::kRgb), scored as the per-channel SSD over 3 · width elements a row.
template <typename T, int kChannels = 1>
class LevelScorer {
 public:
  LevelScorer(const Crop& ref, const Crop& cur, cv::Rect bounds, int level,
              const SlidingSsd* sliding = nullptr)
      : ref_(ref.pyramid[level]),
        cur_(cur.pyramid[level]),
        patch_(LevelPatch(bounds, ref.origin, level)),
        base_(patch_.tl() + (ref.origin - cur.origin) / (1 << level)),
        sliding_(sliding) {}

  bool valid() const {
    return patch_.width > 0 && patch_.height > 0 &&
           (patch_ & cv::Rect(0, 0, ref_.cols, ref_.rows)) == patch_;
  }
  int area() const { return patch_.area(); }

  // Scores the shifts (sx_first … sx_first + count − 1, sy) at once into `out`, or returns
  // false when any of them leaves the current crop.
  bool ScoreRow(int sx_first, int count, int sy, std::vector<std::int64_t>* out) const {
    const cv::Rect span(base_.x + sx_first, base_.y + sy, patch_.width + count - 1, patch_.height);
    if ((span & cv::Rect(0, 0, cur_.cols, cur_.rows)) != span) return false;
    out->assign(static_cast<std::size_t>(count), 0);
    if constexpr (kChannels == 3) {
      // No sliding form for interleaved channels: one block per shift (coarse levels are small).
      for (int i = 0; i < count; ++i) {
        (*out)[static_cast<std::size_t>(i)] =
            SsdBlock(ref_.ptr<T>(patch_.y) + patch_.x * kChannels, ref_.step1(),
                     cur_.ptr<T>(span.y) + (span.x + i) * kChannels, cur_.step1(),
                     patch_.width * kChannels, patch_.height);
      }
    } else if constexpr (sizeof(T) == 1) {
      // 8-bit planes: the reference's patch is prepared for SlidingSsd (ReferenceLevels)
      // whenever the level is valid.
      if (sliding_ == nullptr) return false;
      sliding_->Score(cur_, span.tl(), count, /*along_x=*/true, out->data());
    } else {
      for (int y = 0; y < patch_.height; ++y) {
        SsdSlide(ref_.ptr<T>(patch_.y + y) + patch_.x, patch_.width,
                 cur_.ptr<T>(span.y + y) + span.x, count, out->data());
      }
    }
    return true;
  }
  // The range of sx for which a whole row of shifts stays inside the crop, at `sy`.
  std::pair<int, int> ValidX(int sy) const {
    if (base_.y + sy < 0 || base_.y + sy + patch_.height > cur_.rows) return {1, 0};
    return {-base_.x, cur_.cols - patch_.width - base_.x};
  }

  // SSD at `shift` (level pixels); false outside the current crop.
  bool Score(cv::Point shift, std::int64_t* distance) const {
    const cv::Rect at(base_ + shift, patch_.size());
    if ((at & cv::Rect(0, 0, cur_.cols, cur_.rows)) != at) return false;
    if constexpr (sizeof(T) == 1 && kChannels == 1) {
      if (sliding_ != nullptr) {
        // Whole vectors per row, no remainder loop: faster than SsdBlock on 25- and 50-pixel
        // rows, and the same integer.
        *distance = sliding_->At(cur_, at.tl());
        return true;
      }
    }
    *distance = SsdBlock(ref_.ptr<T>(patch_.y) + patch_.x * kChannels, ref_.step1(),
                         cur_.ptr<T>(at.y) + at.x * kChannels, cur_.step1(),
                         patch_.width * kChannels, patch_.height);
    return true;
  }

 private:
  const cv::Mat& ref_;
  const cv::Mat& cur_;
  cv::Rect patch_;
  cv::Point base_;
  const SlidingSsd* sliding_;
};

// From `start`, re-centres a window of ±(wx, wy) on the lowest scored shift until the centre
// is the lowest. `score(shift, &d)` returns false where a shift cannot be scored.
template <typename ScoreFn>
bool Descend(cv::Point start, int wx, int wy, ScoreFn&& score, ScoreMap* scored, cv::Point* best,
             int max_steps = kMaxDescentSteps) {
  cv::Point centre = start;
  bool any = false;
  for (int step = 0; step < max_steps; ++step) {
    cv::Point lowest = centre;
    std::int64_t lowest_d = -1;
    for (int dy = -wy; dy <= wy; ++dy) {
      for (int dx = -wx; dx <= wx; ++dx) {
        const cv::Point s = centre + cv::Point(dx, dy);
        std::int64_t d = 0;
        if (const std::int64_t* known = scored->find(s)) {
          d = *known;
        } else {
          if (!score(s, &d)) continue;
          scored->emplace(s, d);
        }
        any = true;
        if (lowest_d < 0 || d < lowest_d) {
          lowest_d = d;
          lowest = s;
        }
      }
    }
    if (lowest_d < 0) return any;
    *best = lowest;
    if (lowest == centre) break;
    centre = lowest;
  }
  return any;
}

// The coarse window's error profile along one axis (lowest over the other), for the
// confidence figure.
// A few hundred scores land on a few dozen keys: the lowest per key goes to a flat table
// indexed by key, then out in key order (no tree, no searches).
const std::vector<std::pair<int, std::int64_t>>& Profile(const ScoreMap& scored, bool along_x) {
  const auto key = [along_x](cv::Point s) { return along_x ? s.x : s.y; };
  int lo = key(scored.begin()->first);
  int hi = lo;
  for (const auto& entry : scored) {
    lo = std::min(lo, key(entry.first));
    hi = std::max(hi, key(entry.first));
  }
  const int keys = hi - lo + 1;
  thread_local std::vector<std::int64_t> lowest;
  lowest.assign(static_cast<std::size_t>(keys), -1);  // −1: no score at this key
  for (const auto& [shift, d] : scored) {
    const int index = key(shift) - lo;
    std::int64_t& slot = lowest[static_cast<std::size_t>(index)];
    if (slot < 0 || d < slot) slot = d;
  }
  thread_local std::vector<std::pair<int, std::int64_t>> profile;
  profile.clear();
  for (int i = 0; i < keys; ++i) {
    const std::int64_t d = lowest[static_cast<std::size_t>(i)];
    if (d >= 0) profile.emplace_back(lo + i, d);
  }
  return profile;
}

// Where one search looks: the axes searched, how far, and the crops it wants around the
// patch in the reference and the current frame.
struct SearchWindow {
  bool search_x = true;
  bool search_y = true;
  int reach_x = 0;  // [px] full resolution
  int reach_y = 0;  // [px] full resolution
  int step = 1;     // [px] full-resolution pixels per coarsest-level pixel
  cv::Rect bounds;  // the patch's samples
  cv::Rect ref_want;
  cv::Rect cur_want;
};

SearchWindow WindowFor(const ReferencePatch& reference, const SearchOptions& options, int levels) {
  SearchWindow w;
  w.search_x = options.axis != SearchAxis::kY;
  w.search_y = options.axis != SearchAxis::kX;
  w.reach_x = w.search_x ? options.range : options.cross_range;
  w.reach_y = w.search_y ? options.range : options.cross_range;
  w.step = 1 << levels;
  w.bounds = reference.samples().bounds();
  w.ref_want = cv::Rect(w.bounds.x - kBlurMargin, w.bounds.y - kBlurMargin,
                        w.bounds.width + 2 * kBlurMargin, w.bounds.height + 2 * kBlurMargin);
  const cv::Point o = options.origin;
  w.cur_want = cv::Rect(
      w.ref_want.x + o.x - w.reach_x - w.step, w.ref_want.y + o.y - w.reach_y - w.step,
      w.ref_want.width + 2 * (w.reach_x + w.step), w.ref_want.height + 2 * (w.reach_y + w.step));
  return w;
}

// The reference's reduced crop depends only on the reference: built once per stored
// reference and shared by every later search against it. nullptr: the reference is too
// close to its image's border for this many levels.
template <typename T, int kChannels>
const ReferenceLevels* ReducedReference(const ReferencePatch& reference, const SearchWindow& window,
                                        int levels, std::atomic<std::uint64_t>& built) {
  const auto& ref_any = reference.Derived("pyr/" + std::to_string(levels), [&]() -> std::any {
    ++built;
    ReferenceLevels derived;
    if (!MakeCrop(reference.image(), window.ref_want, levels, &derived.crop)) return {};
    derived.patches.resize(static_cast<std::size_t>(levels) + 1);
    for (int l = 1; l <= levels && sizeof(T) == 1 && kChannels == 1; ++l) {
      const cv::Rect patch = LevelPatch(window.bounds, derived.crop.origin, l);
      const cv::Mat& level = derived.crop.pyramid[static_cast<std::size_t>(l)];
      if (patch.width > 0 && patch.height > 0 &&
          (patch & cv::Rect(0, 0, level.cols, level.rows)) == patch) {
        derived.patches[static_cast<std::size_t>(l)] = SlidingSsd(level(patch));
      }
    }
    return derived;
  });
  return std::any_cast<ReferenceLevels>(&ref_any);
}

// Every shift of the coarse window (±rx, ±ry around `centre`) that stays inside the crop,
// scored a row at a time.
template <typename T, int kChannels>
void ScoreCoarseWindow(const LevelScorer<T, kChannels>& coarse, cv::Point centre, int rx, int ry,
                       ScoreMap* scores) {
  scores->reserve(static_cast<std::size_t>(2 * rx + 1) * static_cast<std::size_t>(2 * ry + 1));
  thread_local std::vector<std::int64_t> row;
  for (int sy = centre.y - ry; sy <= centre.y + ry; ++sy) {
    const auto [lo, hi] = coarse.ValidX(sy);
    const int first = std::max(centre.x - rx, lo);
    const int last = std::min(centre.x + rx, hi);
    if (first > last || !coarse.ScoreRow(first, last - first + 1, sy, &row)) continue;
    for (int i = 0; i <= last - first; ++i) scores->emplace(cv::Point(first + i, sy), row[i]);
  }
}

// How clearly one axis's error profile has one minimum. A profile lowest at either end of the
// shifts scored is no measurement: the view may lie beyond, past the window's reach or the
// frame's edge (a bottom slice's patch cannot shift down, and a view 14-47 px below read 0 px
// at confidence 0.4 and was claimed: text_motion.jpg, boat, slice 9).
double AxisConfidence(const std::vector<std::pair<int, std::int64_t>>& profile) {
  if (profile.size() >= 2) {
    const auto lowest =
        std::min_element(profile.begin(), profile.end(),
                         [](const auto& a, const auto& b) { return a.second < b.second; });
    if (lowest == profile.begin() || lowest == std::prev(profile.end())) return 0.0;
  }
  return MatchConfidence(profile, 1);
}

// How clearly the coarse window's error profile has one minimum along each searched axis
// (1 on an axis not searched).
cv::Point2d CoarseConfidence(const ScoreMap& scores, const SearchWindow& window) {
  return {window.search_x ? AxisConfidence(Profile(scores, true)) : 1.0,
          window.search_y ? AxisConfidence(Profile(scores, false)) : 1.0};
}

// Finer reduced levels: descends from twice the coarser best, all pixels, down to level 1.
// false: a level could not be scored.
template <typename T, int kChannels>
bool DescendReducedLevels(const ReferenceLevels& derived, const Crop& cur, cv::Rect bounds,
                          int levels, cv::Point window, cv::Point* best, SearchResult* result) {
  for (int l = levels - 1; l >= 1; --l) {
    const LevelScorer<T, kChannels> level(derived.crop, cur, bounds, l, derived.patch(l));
    if (!level.valid()) return false;
    ScoreMap scored;
    cv::Point level_best = *best * 2;
    if (!Descend(
            *best * 2, window.x, window.y,
            [&](cv::Point s, std::int64_t* d) { return level.Score(s, d); }, &scored,
            &level_best)) {
      return false;
    }
    result->evaluations += static_cast<int>(scored.size());
    result->pixels_compared += static_cast<std::int64_t>(scored.size()) * level.area();
    *best = level_best;
  }
  return true;
}

// The sub-pixel displacement around the whole-pixel minimum `fine`: a parabola through both
// neighbours along each searched axis (scored by `full` when not yet in `scored`).
template <typename ScoreFn>
cv::Point2d RefineSubpixel(cv::Point fine, const SearchWindow& window, const ScoreFn& full,
                           ScoreMap* scored) {
  cv::Point2d refined(fine);
  for (const bool along_x : {true, false}) {
    if ((along_x && !window.search_x) || (!along_x && !window.search_y)) continue;
    const cv::Point unit = along_x ? cv::Point(1, 0) : cv::Point(0, 1);
    std::int64_t around[3] = {0, 0, 0};
    bool ok = true;
    for (int k = -1; k <= 1 && ok; ++k) {
      const cv::Point s = fine + unit * k;
      if (const std::int64_t* known = scored->find(s)) {
        around[k + 1] = *known;
      } else {
        ok = full(s, &around[k + 1]);
        if (ok) scored->emplace(s, around[k + 1]);
      }
    }
    if (ok) {
      const double offset = ParabolaVertexOffset(around[0], around[1], around[2]);
      (along_x ? refined.x : refined.y) += offset;
    }
  }
  return refined;
}

// Whether the full-resolution answer `fine` stayed within one coarse step of the coarse
// level's `coarse` [px] along both axes. The confidence is the coarse level's (band-passed),
// but the finer levels compare raw brightness and descend up to kMaxDescentSteps: where they
// walk off the coarse answer (an exposure step of 1.6 × pulled them 10–12 px while the coarse
// level stood on the view), the answer is neither level's for sure and must not be trusted
// at the coarse level's confidence. The coarse step quantises the coarse answer by ± step / 2,
// so the levels agree within 2 px on clean frames (at most 3 over 2,500 realistic-world frames).
bool LevelsAgree(cv::Point fine, cv::Point coarse, int step) {
  return std::abs(fine.x - coarse.x) <= step && std::abs(fine.y - coarse.y) <= step;
}

// The coarse-to-fine search (SPEC §2.3): the coarsest level's whole window jointly, a descent
// per finer reduced level, one 3×3 window at full resolution, then the sub-pixel parabola.
template <typename T, int kChannels = 1>
SearchResult SearchPyramid(const ReferencePatch& reference, const cv::Mat& current,
                           const SearchOptions& options, int levels,
                           std::atomic<std::uint64_t>& built) {
  SearchResult result;
  const SearchWindow window = WindowFor(reference, options, levels);
  const ReferenceLevels* derived = ReducedReference<T, kChannels>(reference, window, levels, built);
  thread_local Crop cur;
  if (derived == nullptr || !MakeCrop(current, window.cur_want, levels, &cur)) return result;

  // Coarsest level: the whole window, jointly.
  const LevelScorer<T, kChannels> coarse(derived->crop, cur, window.bounds, levels,
                                         derived->patch(levels));
  if (!coarse.valid()) return result;
  const int step = window.step;
  const cv::Point centre_c(FloorDiv(options.origin.x, step), FloorDiv(options.origin.y, step));
  const int rx = (window.reach_x + step - 1) / step;
  const int ry = (window.reach_y + step - 1) / step;
  ScoreMap coarse_scores;
  ScoreCoarseWindow(coarse, centre_c, rx, ry, &coarse_scores);
  if (coarse_scores.empty()) return result;
  cv::Point best =
      std::min_element(coarse_scores.begin(), coarse_scores.end(),
                       [](const auto& a, const auto& b) { return a.second < b.second; })
          ->first;
  const cv::Point2d confidence = CoarseConfidence(coarse_scores, window);
  const int wx = (window.search_x || options.cross_range > 0) ? 1 : 0;
  const int wy = (window.search_y || options.cross_range > 0) ? 1 : 0;
  if (wx != rx || wy != ry) {
    // Settle the cross axis at the coarse level.
    cv::Point settled = best;
    Descend(
        best, wx, wy, [&](cv::Point s, std::int64_t* d) { return coarse.Score(s, d); },
        &coarse_scores, &settled);
    best = settled;
  }
  const cv::Point coarse_best = best;
  result.evaluations += static_cast<int>(coarse_scores.size());
  result.pixels_compared += static_cast<std::int64_t>(coarse_scores.size()) * coarse.area();

  if (!DescendReducedLevels<T, kChannels>(*derived, cur, window.bounds, levels, {wx, wy}, &best,
                                          &result)) {
    return result;
  }

  // Full resolution: the sampled pixels.
  ScoreMap scored;
  cv::Point fine = best * 2;
  const auto full = [&](cv::Point s, std::int64_t* d) {
    if (!reference.CanShift(current.size(), s)) return false;
    *d = reference.Distance(current, s);
    return true;
  };
  // One 3×3 window, not a descent: at full resolution the brightness drift's pull (see
  // MakeCrop) would walk a descent away from the reduced levels' answer.
  if (!Descend(best * 2, wx, wy, full, &scored, &fine, /*max_steps=*/1)) return result;
  const cv::Point2d refined =
      options.subpixel ? RefineSubpixel(fine, window, full, &scored) : cv::Point2d(fine);
  result.evaluations += static_cast<int>(scored.size());
  result.pixels_compared += static_cast<std::int64_t>(scored.size()) * reference.size();
  result.found = true;
  result.shift = fine;
  result.displacement = refined;
  result.distance = scored.at(fine);
  const double agree = LevelsAgree(fine, coarse_best * step, step) ? 1.0 : 0.0;
  result.confidence_x = agree * confidence.x;
  result.confidence_y = agree * confidence.y;
  result.confidence = std::min(result.confidence_x, result.confidence_y);
  return result;
}

}  // namespace

SearchResult PyramidSearch::Search(const ReferencePatch& reference, const cv::Mat& current,
                                   const SearchOptions& options) const {
  if (reference.type() == CV_8UC1) {
    return SearchPyramid<std::uint8_t>(reference, current, options, levels_, *built_);
  }
  if (reference.type() == CV_16UC1) {
    return SearchPyramid<std::uint16_t>(reference, current, options, levels_, *built_);
  }
  return SearchPyramid<std::uint8_t, 3>(reference, current, options, levels_, *built_);
}

}  // namespace kapfix
