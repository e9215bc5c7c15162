#include "common/control/calibration.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "common/analysis/statistics.hpp"

namespace kapfix {
namespace {

// 1.4826 · MAD estimates σ of normally distributed residuals.
constexpr double kMadToSigma = 1.4826;
constexpr double kInlierSigmas = 3.0;

}  // namespace

AxisCalibration CalibrateAxis(const std::vector<CalibrationSample>& samples) {
  for (const CalibrationSample& s : samples) {
    if (!std::isfinite(s.servo_move) || !std::isfinite(s.displacement_px)) {
      throw std::invalid_argument("CalibrateAxis: a sample is not finite");
    }
  }
  std::vector<double> slopes;  // [px / servo unit]
  for (std::size_t i = 0; i < samples.size(); ++i) {
    for (std::size_t j = i + 1; j < samples.size(); ++j) {
      const double run = samples[j].servo_move - samples[i].servo_move;
      if (run == 0.0) continue;
      slopes.push_back((samples[j].displacement_px - samples[i].displacement_px) / run);
    }
  }
  if (slopes.empty()) {
    throw std::invalid_argument(
        "CalibrateAxis: needs at least 2 samples with different servo moves, got " +
        std::to_string(samples.size()) + " sample(s)");
  }
  const double slope = Median(std::move(slopes));
  if (slope == 0.0) {
    throw std::invalid_argument("CalibrateAxis: zero slope, the view did not move with the servo");
  }

  std::vector<double> ratios;  // [servo units / px]
  int zero_moves = 0;
  for (const CalibrationSample& s : samples) {
    if (s.servo_move == 0.0) ++zero_moves;
    if (s.servo_move != 0.0 && std::abs(s.displacement_px) >= 1.0) {
      ratios.push_back(s.servo_move / s.displacement_px);
    }
  }
  if (ratios.empty()) {
    throw std::invalid_argument(
        "CalibrateAxis: no sample with a servo move and a displacement of at least 1 px");
  }

  AxisCalibration result;
  result.samples = static_cast<int>(samples.size());
  std::vector<double> thesis_ratios = ratios;
  thesis_ratios.insert(thesis_ratios.end(), static_cast<std::size_t>(zero_moves), 0.0);
  result.units_per_px_thesis = Median(std::move(thesis_ratios));
  result.units_per_px_median = Median(std::move(ratios));
  result.units_per_px_fit = 1.0 / slope;

  std::vector<double> intercepts;
  for (const CalibrationSample& s : samples) {
    intercepts.push_back(s.displacement_px - slope * s.servo_move);
  }
  result.offset_px = Median(intercepts);

  std::vector<double> residuals;
  for (const CalibrationSample& s : samples) {
    residuals.push_back(s.displacement_px - (slope * s.servo_move + result.offset_px));
  }
  const double centre = Median(residuals);
  std::vector<double> deviations;
  for (const double r : residuals) deviations.push_back(std::abs(r - centre));
  const double sigma = kMadToSigma * Median(std::move(deviations));
  // With more than half the samples exactly on the line σ is 0; the floor keeps points that
  // are on it up to rounding.
  double largest = 0.0;
  for (const CalibrationSample& s : samples)
    largest = std::max(largest, std::abs(s.displacement_px));
  const double threshold = std::max(kInlierSigmas * sigma, 1e-9 * (1.0 + largest));

  double squares = 0.0;
  for (const double r : residuals) {
    if (std::abs(r - centre) > threshold) continue;
    ++result.inliers;
    squares += r * r;
  }
  // At least half the residuals lie within one MAD of their median, so inliers > 0.
  result.residual_px = std::sqrt(squares / result.inliers);
  return result;
}

std::vector<double> CalibrationMoves(double span, double step) {
  if (!std::isfinite(span) || span < 0.0) {
    throw std::invalid_argument("CalibrationMoves: span must be ≥ 0, got " + std::to_string(span));
  }
  if (!std::isfinite(step) || step <= 0.0) {
    throw std::invalid_argument("CalibrationMoves: step must be > 0, got " + std::to_string(step));
  }
  // Computed from the index, not accumulated, so the thesis's moves come out exact; the small
  // tolerance keeps +span when 2·span / step is an integer up to rounding.
  const auto count = static_cast<std::size_t>(std::floor(2.0 * span / step + 1e-9)) + 1;
  std::vector<double> moves;
  moves.reserve(count);
  for (std::size_t i = 0; i < count; ++i) moves.push_back(-span + static_cast<double>(i) * step);
  return moves;
}

}  // namespace kapfix
