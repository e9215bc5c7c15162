#pragma once

#include <cstdint>
#include <map>
#include <opencv2/core.hpp>

#include "common/matching/reference_patch.hpp"

namespace kapfix {

// Evaluates the distance along one axis through a fixed point, remembering what it has
// scored so that a strategy that revisits a shift (h23's levels share their centre) pays once.
// Shifts outside the frame or outside ±range around the centre are refused.
class AxisProbe {
 public:
  AxisProbe(const ReferencePatch& reference, const cv::Mat& current, bool along_x, cv::Point centre,
            int range);

  // Distance at position `s` on the axis (the shift is centre with its axis component = s);
  // nullopt-like: returns false if `s` cannot be scored.
  bool Evaluate(int s, std::int64_t* distance);
  bool CanEvaluate(int s) const { return interval_.contains(s); }
  // Evaluates every position in [first, last] that can be scored, as Evaluate would one by
  // one (the same distances), but in one sweep when the reference is a dense 8-bit block.
  void EvaluateRun(int first, int last);

  // Best scored position so far (ties: the one closest to the centre, then the smaller).
  bool Best(int* s, std::int64_t* distance) const;
  // Moves `*s` to a lower neighbour while one exists, then returns the sub-pixel position of
  // that minimum (parabola through s − 1, s, s + 1, evaluated on demand); `*s` itself when a
  // neighbour cannot be scored.
  double Refine(int* s);
  // How clearly the best scored position beats its best distinct rival, in [0, 1].
  double Confidence() const;

  cv::Point ShiftAt(int s) const;
  int centre_position() const { return along_x_ ? centre_.x : centre_.y; }
  const std::map<int, std::int64_t>& scored() const { return scored_; }
  int evaluations() const { return static_cast<int>(scored_.size()); }

 private:
  const ReferencePatch& reference_;
  const cv::Mat& current_;
  bool along_x_;
  cv::Point centre_;
  ReferencePatch::ShiftInterval interval_;
  std::map<int, std::int64_t> scored_;
};

}  // namespace kapfix
