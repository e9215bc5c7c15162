#include "common/control/deg_per_px_estimator.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace kapfix {
namespace {

// [frames] how long after a (re)start the estimate is refitted every frame until first trusted.
constexpr int kLockOnFrames = 60;
constexpr int kGridPoints = 49;  // log-spaced θ candidates over the search span
// [1] per row, on the play's columns: a segment in which the servo never reversed leaves them
// equal to the offset's column, and the ridge picks one of the equivalent fits.
constexpr double kPlayRidge = 1e-6;
// [1] a row whose residual is beyond this many (normal-scaled) median absolute residuals of
// its segment is not fitted: a frame seen through another angle than the loop believes (a
// servo command overtaken under latency jitter) or a false match.
constexpr double kOutlierMads = 4.0;
constexpr int kScreenPasses = 3;  // residuals → screen → refit on the kept rows
// [px] the least measurement noise a matcher has (sub-pixel interpolation); the simulated one
// misses by 0.07–0.2 px RMS.
constexpr double kNoiseFloorPx = 0.05;
// [1] a fit moves the estimate only while its σ is below this × max_relative_sigma.
constexpr double kMoveSigmaFactor = 3.0;

// The vertex of a residual curve over the log θ grid (a parabola through the lowest point and
// its neighbours) and σ of log θ from its curvature, σ² = 2·s²/RSS''; false when the minimum
// is at the span's edge (not bracketed) or the curve is not convex there.
// [1] Student's t 97.5 % quantile at `dof` ÷ the normal one (1.96): 1.56 at 3, 1.14 at 10.
double StudentWidening(int dof) {
  constexpr double z = 1.959964;
  const double n = dof;
  const double t =
      z + (z * z * z + z) / (4 * n) + (5 * std::pow(z, 5) + 16 * z * z * z + 3 * z) / (96 * n * n);
  return t / z;
}

bool Vertex(const std::vector<double>& rss, double step, int dof, double* offset_steps, int* best,
            double* sigma) {
  *best = static_cast<int>(std::min_element(rss.begin(), rss.end()) - rss.begin());
  if (*best == 0 || *best == static_cast<int>(rss.size()) - 1) return false;
  const double r0 = rss[*best - 1], r1 = rss[*best], r2 = rss[*best + 1];
  const double curvature = (r0 - 2 * r1 + r2) / (step * step);  // d²RSS/d(log θ)²
  if (!(curvature > 0)) return false;
  *offset_steps = 0.5 * (r0 - r2) / (r0 - 2 * r1 + r2);
  // s² per row, never below a matcher's noise floor: frames that a model fits exactly (no
  // noise, a servo that only followed the swing) would otherwise make any θ certain.
  const double s2 = std::max(r1 / std::max(1, dof), kNoiseFloorPx * kNoiseFloorPx);
  // With few rows beyond the parameters s² is itself uncertain: σ is widened by Student's t
  // against the normal quantile (95 %, Cornish–Fisher to 1/dof²), so a lock-on fit on a
  // dozen rows is trusted only when its interval, not just its point, is narrow.
  *sigma = std::sqrt(2.0 * s2 / curvature) * StudentWidening(std::max(1, dof));
  return true;
}

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
  if (segment_frames < 10 || segment_frames > window_frames) {
    return fail("deg/px estimator segments must be 10…window frames, got " +
                std::to_string(segment_frames));
  }
  if (!(segment_max_relative_sigma > 0 && segment_max_relative_sigma <= 10)) {
    return fail("deg/px estimator segment sigma bound must be in (0, 10], got " +
                std::to_string(segment_max_relative_sigma));
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
  recent_.clear();
  closed_.clear();
  open_rows_.clear();
  open_frames_ = 0;
  last_angle_deg_ = 0;
  moved_ = false;
  direction_ = 0;
  rows_ = 0;
  since_fit_ = 0;
  lock_on_frames_ = 0;
  ever_trusted_ = false;
}

void DegPerPxEstimator::AddMissing() {
  recent_.push_back({0, 0, false, direction_});
  while (static_cast<int>(recent_.size()) > options_.order + 1) recent_.pop_front();
  if (++open_frames_ >= options_.segment_frames) CloseSegment();
}

void DegPerPxEstimator::Add(double angle_deg, double displacement_px) {
  if (!std::isfinite(angle_deg) || !std::isfinite(displacement_px)) {
    AddMissing();
    return;
  }
  if (moved_ && angle_deg != last_angle_deg_) direction_ = angle_deg > last_angle_deg_ ? 1 : -1;
  last_angle_deg_ = angle_deg;
  moved_ = true;
  recent_.push_back({angle_deg, displacement_px, true, direction_});
  while (static_cast<int>(recent_.size()) > options_.order + 1) recent_.pop_front();
  AddRow();
  if (++open_frames_ >= options_.segment_frames) CloseSegment();
  // Until the first trusted fit every frame counts: the lock-on's fits are small, and each
  // frame earlier that the loop acts on the right calibration is a frame less of wrong
  // correction (calibration ×0.6 from the first frame).
  if (++since_fit_ >= options_.refit_every ||
      (!ever_trusted_ && ++lock_on_frames_ <= kLockOnFrames)) {
    since_fit_ = 0;
    Fit();
    ever_trusted_ = ever_trusted_ || trusted();
  }
}

int DegPerPxEstimator::RowSize() const {
  const int p = options_.order;
  return 2 * (p + 1) + 1 + (options_.backlash ? p + 1 : 0);
}

void DegPerPxEstimator::AddRow() {
  const int p = options_.order;
  if (static_cast<int>(recent_.size()) < p + 1) return;
  for (const Sample& s : recent_) {
    if (!s.valid) return;
  }
  const int offset_column = 2 * (p + 1);  // d_t…d_{t−p}, a_t…a_{t−p}, then 1, then s
  Eigen::VectorXd z = Eigen::VectorXd::Zero(RowSize());
  for (int i = 0; i <= p; ++i) {
    const Sample& s = recent_[recent_.size() - 1 - i];  // t − i
    z(i) = s.displacement_px;
    z(p + 1 + i) = s.angle_deg;
    if (options_.backlash) z(offset_column + 1 + i) = s.direction;
  }
  z(offset_column) = 1.0;
  open_rows_.push_back(z);
}

void DegPerPxEstimator::CloseSegment() {
  closed_.push_back(Screened(open_rows_, open_frames_));
  open_rows_.clear();
  open_frames_ = 0;
  int frames = 0;
  for (const Segment& s : closed_) frames += s.frames;
  // Whole segments, the open one included, within the window.
  while (frames > options_.window_frames - options_.segment_frames && !closed_.empty()) {
    frames -= closed_.front().frames;
    closed_.pop_front();
  }
}

double DegPerPxEstimator::GridTheta(int i) const {
  // Log-spaced over [1/max_ratio, max_ratio] × the start, with the start's sign.
  const double start = 1.0 / start_deg_per_px_;  // [px/deg], signed
  const double log_lo = std::log(std::abs(start) / options_.max_ratio);
  return std::copysign(std::exp(log_lo + i * GridStep()), start);
}

double DegPerPxEstimator::GridStep() const {
  return 2.0 * std::log(options_.max_ratio) / (kGridPoints - 1);
}

Eigen::MatrixXd DegPerPxEstimator::Transform(double theta) const {
  // (u_t, u_{t−1}…u_{t−p}, 1, s_t…s_{t−p}) = T·z with u = d + θ·a.
  const int p = options_.order;
  const int q = options_.backlash ? p + 1 : 0;
  Eigen::MatrixXd t = Eigen::MatrixXd::Zero(p + 2 + q, RowSize());
  for (int i = 0; i <= p; ++i) {
    t(i, i) = 1.0;
    t(i, p + 1 + i) = theta;
  }
  const int offset_column = 2 * (p + 1);
  t(p + 1, offset_column) = 1.0;
  for (int i = 0; i < q; ++i) t(p + 2 + i, offset_column + 1 + i) = 1.0;
  return t;
}

double DegPerPxEstimator::SwingModel(const Segment& segment, double theta,
                                     Eigen::VectorXd* coefficients) const {
  // u_t = α1·u_{t−1} + … + αp·u_{t−p} + c + Σ γi·s_{t−i} by least squares; the Gram matrix
  // of (u_t, u_{t−1}…u_{t−p}, 1, s_t…s_{t−p}) is T·sums·Tᵀ.
  const int p = options_.order;
  if (segment.rows < 3 * (p + 1)) return std::numeric_limits<double>::quiet_NaN();
  const Eigen::MatrixXd t = Transform(theta);
  const Eigen::MatrixXd gram = t * segment.sums * t.transpose();
  const int n = static_cast<int>(gram.rows());
  Eigen::MatrixXd ata = gram.bottomRightCorner(n - 1, n - 1);
  for (int i = p + 1; i < n - 1; ++i) ata(i, i) += kPlayRidge * segment.rows;
  const Eigen::VectorXd atb = gram.col(0).tail(n - 1);
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(ata);
  if (ldlt.info() != Eigen::Success) return std::numeric_limits<double>::quiet_NaN();
  const Eigen::VectorXd w = ldlt.solve(atb);
  if (coefficients) *coefficients = w;
  // RSS = bᵀb − wᵀAᵀb for the least-squares w.
  return std::max(0.0, gram(0, 0) - w.dot(atb));
}

std::vector<double> DegPerPxEstimator::Curve(const Segment& segment) const {
  std::vector<double> rss(kGridPoints);
  for (int i = 0; i < kGridPoints; ++i) rss[i] = SwingModel(segment, GridTheta(i), nullptr);
  return rss;
}

DegPerPxEstimator::Segment DegPerPxEstimator::Screened(const std::vector<Eigen::VectorXd>& rows,
                                                       int frames) const {
  const auto sum = [&](const std::vector<bool>& keep) {
    Segment s{Eigen::MatrixXd::Zero(RowSize(), RowSize()), 0, frames};
    for (std::size_t k = 0; k < rows.size(); ++k) {
      if (!keep.empty() && !keep[k]) continue;
      s.sums += rows[k] * rows[k].transpose();
      ++s.rows;
    }
    return s;
  };
  // The residuals are taken at the trusted estimate, else at the segment's own best θ: at a
  // θ far off, the rows where the servo stepped would look like outliers. Outliers pull the
  // own θ and the swing model too, so the screen is repeated on what it kept.
  std::vector<bool> keep;
  for (int pass = 0; pass < kScreenPasses; ++pass) {
    const Segment kept = sum(keep);
    double theta = 1.0 / estimate_deg_per_px_;
    if (!trusted()) {
      double offset = 0, sigma = 0;
      int best = 0;
      if (Vertex(Curve(kept), GridStep(), kept.rows - 1, &offset, &best, &sigma)) {
        theta = GridTheta(best) * std::exp(offset * GridStep());
      }
    }
    Eigen::VectorXd w;
    if (!std::isfinite(SwingModel(kept, theta, &w))) break;
    const Eigen::MatrixXd t = Transform(theta);
    std::vector<double> magnitude, inliers;
    for (std::size_t k = 0; k < rows.size(); ++k) {
      const Eigen::VectorXd u = t * rows[k];
      magnitude.push_back(std::abs(u(0) - w.dot(u.tail(u.size() - 1))));
      if (keep.empty() || keep[k]) inliers.push_back(magnitude.back());
    }
    const auto middle = inliers.begin() + static_cast<std::ptrdiff_t>(inliers.size() / 2);
    std::nth_element(inliers.begin(), middle, inliers.end());
    const double limit = kOutlierMads * 1.4826 * *middle;
    if (!(limit > 0)) break;
    keep.assign(rows.size(), true);
    for (std::size_t k = 0; k < rows.size(); ++k) keep[k] = magnitude[k] <= limit;
  }
  return sum(keep);
}

void DegPerPxEstimator::Fit() {
  const int per_segment = options_.order + 1 + (options_.backlash ? options_.order + 1 : 0);
  std::vector<Segment> open;
  if (static_cast<int>(open_rows_.size()) >= 3 * (options_.order + 1)) {
    open.push_back(Screened(open_rows_, open_frames_));
  }
  // Each segment's own residual curve; a segment whose own curve pins θ down within
  // segment_max_relative_sigma joins the sum. One that does not (the servo only followed the
  // swing) carries no information on θ, only the slope that its measurement noise gives
  // the residual — summed over a long hold, that slope would carry the estimate away.
  std::vector<double> total(kGridPoints, 0.0);
  int rows = 0, parameters = 1;  // θ
  std::vector<const Segment*> segments;
  for (const Segment& s : closed_) segments.push_back(&s);
  for (const Segment& s : open) segments.push_back(&s);
  for (const Segment* s : segments) {
    if (s->rows < 3 * (options_.order + 1)) continue;
    const std::vector<double> curve = Curve(*s);
    double offset = 0, sigma = 0;
    int best = 0;
    if (!std::all_of(curve.begin(), curve.end(), [](double r) { return std::isfinite(r); }) ||
        !Vertex(curve, GridStep(), s->rows - per_segment - 1, &offset, &best, &sigma) ||
        sigma > options_.segment_max_relative_sigma) {
      continue;
    }
    for (int i = 0; i < kGridPoints; ++i) total[i] += curve[i];
    rows += s->rows;
    parameters += per_segment;
  }
  if (rows == 0) return;
  rows_ = rows;
  double offset = 0, sigma = 0;
  int best = 0;
  if (!Vertex(total, GridStep(), rows - parameters, &offset, &best, &sigma)) {
    relative_sigma_ = std::numeric_limits<double>::infinity();
    return;
  }
  relative_sigma_ = sigma;  // σ of log θ ≈ σ_θ/θ
  // A fit this uncertain does not move the estimate, which telemetry and the flight report
  // show whether trusted or not (a kite's small tilt swing once set it 39 % off at σ 23 %).
  if (sigma > kMoveSigmaFactor * options_.max_relative_sigma) return;
  estimate_deg_per_px_ = 1.0 / (GridTheta(best) * std::exp(offset * GridStep()));
}

bool DegPerPxEstimator::trusted() const {
  return rows_ >= options_.min_samples && relative_sigma_ <= options_.max_relative_sigma;
}

}  // namespace kapfix
