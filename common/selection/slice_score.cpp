#include "common/selection/slice_score.hpp"

#include <algorithm>
#include <cstdlib>

namespace kapfix {

std::optional<SliceScoreKind> ParseSliceScoreKind(std::string_view text) {
  if (text == "dc") return SliceScoreKind::kDc;
  if (text == "dc-hyst") return SliceScoreKind::kDcHysteresis;
  if (text == "fft") return SliceScoreKind::kFft;
  if (text == "single-shot") return SliceScoreKind::kSingleShot;
  return std::nullopt;
}

std::string_view ToString(SliceScoreKind kind) {
  switch (kind) {
    case SliceScoreKind::kDc:
      return "dc";
    case SliceScoreKind::kDcHysteresis:
      return "dc-hyst";
    case SliceScoreKind::kFft:
      return "fft";
    case SliceScoreKind::kSingleShot:
      return "single-shot";
  }
  return "?";
}

namespace {

// The chosen score turned into "lower is better".
double Key(const SliceScore& s, SliceScoreKind kind) {
  switch (kind) {
    case SliceScoreKind::kDc:
      return s.dc;
    case SliceScoreKind::kDcHysteresis:
      return s.dc_hysteresis;
    case SliceScoreKind::kFft:
      return s.fft;
    case SliceScoreKind::kSingleShot:
      return -s.single_shot;
  }
  return 0.0;
}

}  // namespace

std::vector<int> RankSlices(const std::vector<SliceScore>& scores, SliceScoreKind kind,
                            int slice_count) {
  int count = slice_count;
  if (count <= 0) {
    for (const SliceScore& s : scores) count = std::max(count, s.index);
  }
  // Twice the distance to the centre slice (count + 1) / 2, kept in integers.
  auto off_centre = [count](const SliceScore& s) { return std::abs(2 * s.index - (count + 1)); };
  std::vector<const SliceScore*> order;
  order.reserve(scores.size());
  for (const SliceScore& s : scores) order.push_back(&s);
  std::stable_sort(order.begin(), order.end(), [&](const SliceScore* a, const SliceScore* b) {
    if (a->ambiguous != b->ambiguous) return b->ambiguous;
    const double ka = Key(*a, kind);
    const double kb = Key(*b, kind);
    if (ka != kb) return ka < kb;
    if (a->fft != b->fft) return a->fft < b->fft;
    if (off_centre(*a) != off_centre(*b)) return off_centre(*a) < off_centre(*b);
    return a->index < b->index;
  });
  std::vector<int> ranking;
  ranking.reserve(order.size());
  for (const SliceScore* s : order) ranking.push_back(s->index);
  return ranking;
}

}  // namespace kapfix
