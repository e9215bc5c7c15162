#include "common/search/axis_probe.hpp"

#include <algorithm>
#include <cstdlib>
#include <iterator>
#include <vector>

#include "common/matching/sliding_ssd.hpp"
#include "common/search/match_confidence.hpp"
#include "common/search/subpixel.hpp"

namespace kapfix {

AxisProbe::AxisProbe(const ReferencePatch& reference, const cv::Mat& current, bool along_x,
                     cv::Point centre, int range)
    : reference_(reference), current_(current), along_x_(along_x), centre_(centre) {
  // The frame's limits for this axis, through the centre's other coordinate.
  const cv::Size frame = current.size();
  const int other = along_x ? centre.y : centre.x;
  const bool other_fits = along_x
                              ? reference.ShiftRangeY(frame, std::abs(other) + 1).contains(other)
                              : reference.ShiftRangeX(frame, std::abs(other) + 1).contains(other);
  if (!other_fits) return;  // interval_ stays empty
  const int c = along_x ? centre.x : centre.y;
  const auto limits = along_x ? reference.ShiftRangeX(frame, std::abs(c) + range)
                              : reference.ShiftRangeY(frame, std::abs(c) + range);
  interval_ = {std::max(limits.first, c - range), std::min(limits.last, c + range)};
}

cv::Point AxisProbe::ShiftAt(int s) const {
  return along_x_ ? cv::Point(s, centre_.y) : cv::Point(centre_.x, s);
}

bool AxisProbe::Evaluate(int s, std::int64_t* distance) {
  if (!CanEvaluate(s)) return false;
  const auto it = scored_.find(s);
  if (it != scored_.end()) {
    *distance = it->second;
    return true;
  }
  *distance = reference_.Distance(current_, ShiftAt(s));
  scored_.emplace(s, *distance);
  return true;
}

void AxisProbe::EvaluateRun(int first, int last) {
  first = std::max(first, interval_.first);
  last = std::min(last, interval_.last);
  if (first > last) return;
  const SlidingSsd* sliding =
      current_.type() == CV_8UC1 ? SlidingSsd::ForReference(reference_) : nullptr;
  if (sliding == nullptr) {
    std::int64_t distance = 0;
    for (int s = first; s <= last; ++s) Evaluate(s, &distance);
    return;
  }
  thread_local std::vector<std::int64_t> distances;
  distances.resize(static_cast<std::size_t>(last) - first + 1);
  sliding->Score(current_, reference_.samples().bounds().tl() + ShiftAt(first),
                 static_cast<int>(distances.size()), along_x_, distances.data());
  auto hint = scored_.lower_bound(first);
  for (int s = first; s <= last; ++s) {
    hint = std::next(scored_.emplace_hint(hint, s, distances[static_cast<std::size_t>(s - first)]));
  }
}

bool AxisProbe::Best(int* s, std::int64_t* distance) const {
  if (scored_.empty()) return false;
  const int c = centre_position();
  auto best = scored_.begin();
  for (auto it = scored_.begin(); it != scored_.end(); ++it) {
    if (it->second < best->second ||
        (it->second == best->second && std::abs(it->first - c) < std::abs(best->first - c))) {
      best = it;
    }
  }
  *s = best->first;
  *distance = best->second;
  return true;
}

double AxisProbe::Refine(int* s) {
  // Step to a lower neighbour while there is one (a coarse strategy's last level may step by
  // more than one pixel), then fit the parabola through the minimum and its neighbours.
  constexpr int kMaxSteps = 8;
  std::int64_t left = 0;
  std::int64_t centre = 0;
  std::int64_t right = 0;
  for (int step = 0; step < kMaxSteps; ++step) {
    if (!Evaluate(*s, &centre)) return *s;
    const bool has_left = Evaluate(*s - 1, &left);
    const bool has_right = Evaluate(*s + 1, &right);
    if (has_left && left < centre && (!has_right || left <= right)) {
      --*s;
    } else if (has_right && right < centre) {
      ++*s;
    } else {
      if (!has_left || !has_right) return *s;
      return *s + ParabolaVertexOffset(left, centre, right);
    }
  }
  return *s;
}

double AxisProbe::Confidence() const { return MatchConfidence(scored_); }

}  // namespace kapfix
