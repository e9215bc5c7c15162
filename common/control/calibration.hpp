#pragma once

#include <vector>

namespace kapfix {

// One calibration move (SPEC §2.7, thesis §4.2): the servo was moved by servo_move from the
// reference position and the view was found displaced by displacement_px.
struct CalibrationSample {
  double servo_move = 0.0;       // [servo units]
  double displacement_px = 0.0;  // [px] along the axis the servo turns
};

// Servo units per pixel for one axis, two ways.
struct AxisCalibration {
  // Thesis: median of the ratios servo_move / displacement over the samples with
  // |displacement| ≥ 1 px and servo_move ≠ 0 (smaller displacements make the ratio explode).
  // Any constant offset in the displacements (Table 4.1 reads −4 px at a zero move) biases it.
  double units_per_px_median = 0.0;  // [servo units / px]
  // The thesis's own counting (Table 4.1, "Median(C1…C5) = 1.11"): the same median, but every
  // zero-move sample enters as a ratio of 0, as the table's C columns print it. On the table's
  // 105 entries this gives its 1.11 where the rule above gives 1.21; the five zeros pull the
  // median down three places. Reported for comparison with the thesis, never used to control.
  double units_per_px_thesis = 0.0;  // [servo units / px]
  // 1 / slope of the robust line displacement = slope · servo_move + offset (Theil–Sen: the
  // median of the pairwise slopes, then the median intercept), which absorbs the offset.
  double units_per_px_fit = 0.0;  // [servo units / px]
  double offset_px = 0.0;         // [px] the line's displacement at a zero move
  double residual_px = 0.0;       // [px] RMS residual of the line over its inliers
  int samples = 0;                // samples given
  int inliers = 0;  // samples within 3σ of the line, σ = 1.4826 · MAD of the residuals
};

// Throws std::invalid_argument naming the problem: a non-finite sample, fewer than 2 samples
// with different servo moves (no slope), a zero slope (the view did not move), or no sample
// usable for the ratio median.
AxisCalibration CalibrateAxis(const std::vector<CalibrationSample>& samples);

// The moves of one calibration round: −span, −span + step, … up to +span (thesis: −100 … +100
// in steps of 10, 21 moves) [servo units]. Throws std::invalid_argument unless span ≥ 0 and
// step > 0.
std::vector<double> CalibrationMoves(double span = 100, double step = 10);

}  // namespace kapfix
