#include "common/control/deg_per_px_estimator.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

constexpr int kGridPoints = 49;  // log-spaced θ candidates over the search span

}  // namespace

bool DegPerPxEstimatorOptions::IsValid(std::string* error) const {
  auto fail = [error](const std::string& message) {
    if (error) *error = message;
    return false;
  };
  if (order < 1 || order > 8) {
    return fail("deg/px estimator swing model order must be 1…8, got " + std::to_string(order));
  }
  if (window_frames < 20 || window_frames > 10000) {
    return fail("deg/px estimator window must be 20…10000 frames, got " +
                std::to_string(window_frames));
  }
  if (min_samples < 10 || min_samples > window_frames) {
    return fail("deg/px estimator needs 10…window samples before trust, got " +
                std::to_string(min_samples));
  }
  if (refit_every < 1 || refit_every > window_frames) {
    return fail("deg/px estimator refits every 1…window frames, got " +
                std::to_string(refit_every));
  }
  if (!(max_relative_sigma > 0 && max_relative_sigma <= 1)) {
    return fail("deg/px estimator relative sigma must be in (0, 1], got " +
                std::to_string(max_relative_sigma));
  }
  if (!(max_ratio > 1 && max_ratio <= 100)) {
    return fail("deg/px estimator ratio bound must be in (1, 100], got " +
                std::to_string(max_ratio));
  }
  return true;
}

DegPerPxEstimator::DegPerPxEstimator(double start_deg_per_px, DegPerPxEstimatorOptions options)
    : options_(options) {
  std::string error;
  if (!options_.IsValid(&error)) throw std::invalid_argument("DegPerPxEstimator: " + error);
  Restart(start_deg_per_px);
}

void DegPerPxEstimator::Restart(double start_deg_per_px) {
  if (!std::isfinite(start_deg_per_px) || start_deg_per_px == 0) {
    throw std::invalid_argument(
        "DegPerPxEstimator: start deg/px must be finite and non-zero, got " +
        std::to_string(start_deg_per_px));
  }
  start_deg_per_px_ = start_deg_per_px;
  estimate_deg_per_px_ = start_deg_per_px;
  relative_sigma_ = std::numeric_limits<double>::infinity();
  window_.clear();
  rows_ = 0;
  since_fit_ = 0;
}

void DegPerPxEstimator::AddMissing() {
  window_.push_back({0, 0, false});
  while (static_cast<int>(window_.size()) > options_.window_frames) window_.pop_front();
}

void DegPerPxEstimator::Add(double angle_deg, double displacement_px) {
  if (!std::isfinite(angle_deg) || !std::isfinite(displacement_px)) {
    AddMissing();
    return;
  }
  window_.push_back({angle_deg, displacement_px, true});
  while (static_cast<int>(window_.size()) > options_.window_frames) window_.pop_front();
  if (++since_fit_ >= options_.refit_every) {
    since_fit_ = 0;
    Fit();
  }
}

double DegPerPxEstimator::ResidualSumOfSquares(double theta, int* rows) const {
  // Normal equations of u_t = α1·u_{t−1} + … + αp·u_{t−p} + c over rows whose p + 1 frames
  // are all measured.
  const int p = options_.order;
  Eigen::MatrixXd ata = Eigen::MatrixXd::Zero(p + 1, p + 1);
  Eigen::VectorXd atb = Eigen::VectorXd::Zero(p + 1);
  Eigen::VectorXd x(p + 1);
  double btb = 0;
  int n = 0;
  const int size = static_cast<int>(window_.size());
  for (int t = p; t < size; ++t) {
    bool valid = true;
    for (int i = 0; i <= p && valid; ++i) valid = window_[t - i].valid;
    if (!valid) continue;
    const double u0 = window_[t].displacement_px + theta * window_[t].angle_deg;
    for (int i = 1; i <= p; ++i) {
      x(i - 1) = window_[t - i].displacement_px + theta * window_[t - i].angle_deg;
    }
    x(p) = 1.0;
    ata += x * x.transpose();
    atb += x * u0;
    btb += u0 * u0;
    ++n;
  }
  *rows = n;
  if (n < 3 * (p + 1)) return std::numeric_limits<double>::quiet_NaN();
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(ata);
  if (ldlt.info() != Eigen::Success) return std::numeric_limits<double>::quiet_NaN();
  const Eigen::VectorXd w = ldlt.solve(atb);
  // RSS = bᵀb − wᵀAᵀb for the least-squares w.
  return std::max(0.0, btb - w.dot(atb));
}

void DegPerPxEstimator::Fit() {
  const double start = 1.0 / start_deg_per_px_;  // [px/deg], signed
  const double sign = std::copysign(1.0, start);
  const double log_lo = std::log(std::abs(start) / options_.max_ratio);
  const double log_hi = std::log(std::abs(start) * options_.max_ratio);
  const double step = (log_hi - log_lo) / (kGridPoints - 1);
  std::vector<double> rss(kGridPoints);
  int rows = 0;
  int best = -1;
  for (int i = 0; i < kGridPoints; ++i) {
    rss[i] = ResidualSumOfSquares(sign * std::exp(log_lo + i * step), &rows);
    if (!std::isfinite(rss[i])) return;
    if (best < 0 || rss[i] < rss[best]) best = i;
  }
  rows_ = rows;
  // A parabola through the best grid point and its neighbours, in log θ: its vertex is the
  // estimate, its curvature the uncertainty. At the span's edge the minimum is not bracketed.
  if (best == 0 || best == kGridPoints - 1) {
    relative_sigma_ = std::numeric_limits<double>::infinity();
    return;
  }
  const double r0 = rss[best - 1], r1 = rss[best], r2 = rss[best + 1];
  const double curvature = (r0 - 2 * r1 + r2) / (step * step);  // d²RSS/d(log θ)²
  if (!(curvature > 0)) {
    relative_sigma_ = std::numeric_limits<double>::infinity();
    return;
  }
  const double offset = 0.5 * step * (r0 - r2) / (r0 - 2 * r1 + r2);
  const double log_theta = log_lo + best * step + offset;
  estimate_deg_per_px_ = sign / std::exp(log_theta);
  // s² from the residual at the minimum (four unknowns: α1, α2, c, θ).
  const double s2 = r1 / std::max(1, rows - options_.order - 2);
  relative_sigma_ = std::sqrt(2.0 * s2 / curvature);  // σ of log θ ≈ σ_θ/θ
}

bool DegPerPxEstimator::trusted() const {
  return rows_ >= options_.min_samples && relative_sigma_ <= options_.max_relative_sigma;
}

}  // namespace kapfix
