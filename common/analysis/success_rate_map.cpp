#include "common/analysis/success_rate_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#include "common/analysis/statistics.hpp"

namespace kapfix {
namespace {

// Slope along the unit step `axis` ((1, 0) or (0, 1)) from up to three points.
double Slope(const ErrorSurface& surface, cv::Point at, cv::Point axis) {
  const cv::Point before = at - axis;
  const cv::Point after = at + axis;
  const bool has_before = surface.Valid(before.x, before.y);
  const bool has_after = surface.Valid(after.x, after.y);
  if (has_before && has_after) {
    return 0.5 * (surface.At(after.x, after.y) - surface.At(before.x, before.y));
  }
  if (has_after) return surface.At(after.x, after.y) - surface.At(at.x, at.y);
  if (has_before) return surface.At(at.x, at.y) - surface.At(before.x, before.y);
  return 0.0;
}

bool IsLocalMinimum(const ErrorSurface& surface, cv::Point at) {
  const double here = surface.At(at.x, at.y);
  for (const cv::Point step :
       {cv::Point(1, 0), cv::Point(-1, 0), cv::Point(0, 1), cv::Point(0, -1)}) {
    const cv::Point n = at + step;
    if (surface.Valid(n.x, n.y) && surface.At(n.x, n.y) < here) return false;
  }
  return true;
}

// round(−gain · slope / scale), limited first so that a huge slope cannot overflow an int.
int StepCells(double slope, double gain, double scale, int range) {
  const double limit = 2.0 * range + 1.0;
  const double cells = std::clamp(-gain * slope / scale, -limit, limit);
  return static_cast<int>(std::lround(cells));
}

// The part of a `cells`-long step along `axis` from `from` that stays on valid cells: it stops
// before the first invalid cell or the range edge, as a servo stops at its end stop.
int ClampToValid(const ErrorSurface& surface, cv::Point from, cv::Point axis, int cells) {
  const int direction = cells > 0 ? 1 : -1;
  int taken = 0;
  while (taken != cells) {
    const cv::Point next = from + axis * (taken + direction);
    if (!surface.Valid(next.x, next.y)) break;
    taken += direction;
  }
  return taken;
}

void RequireSurfaceGeometry(const ErrorSurface& surface) {
  const int side = 2 * surface.range + 1;
  if (surface.range < 0 || surface.distance.type() != CV_64FC1 || surface.distance.rows != side ||
      surface.distance.cols != side) {
    throw std::invalid_argument(
        "success-rate map: the surface must be a CV_64FC1 matrix of side 2 * range + 1");
  }
}

}  // namespace

bool DescentOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (max_steps < 0) return fail("descent max_steps must be ≥ 0, got " + std::to_string(max_steps));
  if (!std::isfinite(initial_gain) || initial_gain <= 0.0) {
    return fail("descent initial_gain must be > 0, got " + std::to_string(initial_gain));
  }
  // A zero step would raise the gain forever without reaching max_gain.
  if (!std::isfinite(gain_step) || gain_step <= 0.0) {
    return fail("descent gain_step must be > 0, got " + std::to_string(gain_step));
  }
  if (!std::isfinite(max_gain) || max_gain < initial_gain) {
    return fail("descent max_gain must be ≥ initial_gain (" + std::to_string(initial_gain) +
                "), got " + std::to_string(max_gain));
  }
  return true;
}

double SurfaceSlopeScale(const ErrorSurface& surface) {
  RequireSurfaceGeometry(surface);
  std::vector<double> differences;
  const int r = surface.range;
  for (int y = -r; y <= r; ++y) {
    for (int x = -r; x <= r; ++x) {
      if (!surface.Valid(x, y)) continue;
      for (const cv::Point axis : {cv::Point(1, 0), cv::Point(0, 1)}) {
        const cv::Point before = cv::Point(x, y) - axis;
        const cv::Point after = cv::Point(x, y) + axis;
        if (!surface.Valid(before.x, before.y) || !surface.Valid(after.x, after.y)) continue;
        const double d =
            0.5 * std::abs(surface.At(after.x, after.y) - surface.At(before.x, before.y));
        if (d > 0.0) differences.push_back(d);
      }
    }
  }
  if (differences.empty()) return 1.0;
  return Median(std::move(differences));
}

DescentResult Descend(const ErrorSurface& surface, cv::Point start, double slope_scale,
                      const DescentOptions& options) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  RequireSurfaceGeometry(surface);
  if (!std::isfinite(slope_scale) || slope_scale <= 0.0) {
    throw std::invalid_argument("Descend: slope scale must be positive and finite");
  }
  if (!surface.Valid(start.x, start.y)) {
    throw std::invalid_argument("Descend: start (" + std::to_string(start.x) + ", " +
                                std::to_string(start.y) + ") is not a valid surface cell");
  }
  const int r = surface.range;
  DescentResult result;
  result.end = start;
  double gain = options.initial_gain;
  while (true) {
    if (IsLocalMinimum(surface, result.end)) {
      result.stop = DescentStop::kLocalMinimum;
      return result;
    }
    if (result.steps >= options.max_steps) {
      result.stop = DescentStop::kStepLimit;
      return result;
    }
    const double slope_x = Slope(surface, result.end, {1, 0});
    const double slope_y = Slope(surface, result.end, {0, 1});
    // Each axis is clamped on its own; on a real surface the valid cells form a rectangle (the
    // shifts that keep the sampled pixels in the frame), so the combined target is then valid.
    // Elsewhere an invalid combined target counts as "would not move".
    const cv::Point target =
        result.end +
        cv::Point(
            ClampToValid(surface, result.end, {1, 0}, StepCells(slope_x, gain, slope_scale, r)),
            ClampToValid(surface, result.end, {0, 1}, StepCells(slope_y, gain, slope_scale, r)));
    if (target != result.end && surface.Valid(target.x, target.y)) {
      result.end = target;
      ++result.steps;
      gain = options.initial_gain;
      continue;
    }
    if (gain >= options.max_gain) {
      result.stop = DescentStop::kGainExhausted;
      return result;
    }
    gain = std::min(gain + options.gain_step, options.max_gain);
  }
}

SuccessRateMap ComputeSuccessRateMap(const ErrorSurface& surface, const DescentOptions& options,
                                     const std::function<void(int, int)>& progress) {
  std::string error;
  if (!options.IsValid(&error)) throw std::invalid_argument(error);
  RequireSurfaceGeometry(surface);
  const int r = surface.range;
  const int side = 2 * r + 1;
  SuccessRateMap map;
  map.success = cv::Mat::zeros(side, side, CV_8UC1);
  const cv::Point goal = surface.ArgMin();
  // ArgMin falls back to (0, 0) when nothing is valid.
  if (!surface.Valid(goal.x, goal.y)) {
    throw std::invalid_argument("success-rate map: the surface has no valid cell");
  }
  const double scale = SurfaceSlopeScale(surface);
  int successes = 0;
  for (int y = -r; y <= r; ++y) {
    for (int x = -r; x <= r; ++x) {
      if (!surface.Valid(x, y)) continue;
      ++map.starts;
      const DescentResult run = Descend(surface, {x, y}, scale, options);
      if (run.end != goal) continue;
      map.success.at<std::uint8_t>(r + y, r + x) = 1;
      ++successes;
      ++map.steps_histogram[run.steps];
    }
    if (progress) progress(y + r + 1, side);
  }
  map.success_pct = 100.0 * successes / map.starts;
  return map;
}

ThesisSurfaceSampling ThesisTable32Sampling(SamplingKind kind, std::uint32_t seed) {
  if (kind == SamplingKind::kAll) {
    throw std::invalid_argument("ThesisTable32Sampling: Table 3.2 has static and random only");
  }
  // The static pattern keeps 10 of every 55 pixels, so the side is near sqrt(14,600 · 5.5).
  SamplingOptions static_sampling;
  static_sampling.kind = SamplingKind::kStatic;
  int side = static_cast<int>(std::floor(std::sqrt(kThesisStaticPixels * 5.5))) - 4;
  while (static_cast<int>(MakeSamplingPattern({side, side}, static_sampling).size()) <
         kThesisStaticPixels) {
    ++side;
  }
  ThesisSurfaceSampling result;
  result.patch_side = side;
  if (kind == SamplingKind::kStatic) {
    result.sampling = static_sampling;
  } else {
    result.sampling.kind = SamplingKind::kRandom;
    result.sampling.seed = seed;
    result.sampling.fraction = static_cast<double>(kThesisRandomPixels) / (side * side);
  }
  result.sampled_pixels =
      static_cast<int>(MakeSamplingPattern({side, side}, result.sampling).size());
  return result;
}

}  // namespace kapfix
