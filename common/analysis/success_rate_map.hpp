#pragma once

#include <functional>
#include <map>
#include <opencv2/core.hpp>
#include <string>

#include "common/matching/error_surface.hpp"
#include "common/sampling/sampling_pattern.hpp"

namespace kapfix {

// The thesis's "P" controller (chapter 3, Fig. 3.30), used only to judge how well an error
// surface can be descended (SPEC §2.9), not to drive servos.
//
// At shift (x, y) it reads the slope per axis from three points, (S(x+1) − S(x−1)) / 2
// (one-sided at the range edge or next to an invalid cell, 0 with no valid neighbour), divides
// it by the surface's slope scale (SurfaceSlopeScale) and moves round(−gain · slope / scale)
// cells per axis. Each axis's step is cut short before the first invalid (NaN) cell or the
// range edge along that axis. When it would not move — both steps 0, or the combined target
// invalid — and it is not at a local minimum, the gain rises by gain_step (the thesis's remedy
// for flat regions); after every move the gain is reset to initial_gain.
struct DescentOptions {
  int max_steps = 500;        // moves before giving up; also ends oscillations
  double initial_gain = 1.0;  // [cells per unit of normalised slope]; thesis: 1
  double gain_step = 1.0;     // added to the gain each time it would not move
  double max_gain = 64.0;     // stop when not even this gain moves it

  bool IsValid(std::string* error) const;
};

enum class DescentStop {
  kLocalMinimum,   // no valid 4-neighbour is lower
  kGainExhausted,  // would not move even at max_gain
  kStepLimit,      // max_steps moves made
};

struct DescentResult {
  cv::Point end{0, 0};  // [px] shift where the controller stopped
  int steps = 0;        // moves made (gain raises are not moves)
  DescentStop stop = DescentStop::kLocalMinimum;
};

// Median of the non-zero absolute central differences |S(x+1) − S(x−1)| / 2 along both axes,
// over every cell whose two neighbours are valid; 1 when there are none. Dividing the slope by
// it makes the controller independent of the surface's units (SSD grows with the number of
// sampled pixels) so a gain of 1 means "one cell for a typical slope". Zeros are skipped so a
// surface that is mostly flat still gets the scale of its sloping part.
double SurfaceSlopeScale(const ErrorSurface& surface);

// Runs the controller from a valid start; throws std::invalid_argument for an invalid start,
// invalid options, a malformed surface or a scale that is not positive and finite.
DescentResult Descend(const ErrorSurface& surface, cv::Point start, double slope_scale,
                      const DescentOptions& options);

struct SuccessRateMap {
  cv::Mat success;                     // CV_8UC1, same geometry as the surface: 1 = start succeeded
  double success_pct = 0.0;            // [%] successful starts / starts
  int starts = 0;                      // valid cells (every valid cell is a start)
  std::map<int, int> steps_histogram;  // steps -> count of successful starts
};

// Descends from every valid cell; a start succeeds if the controller stops at
// surface.ArgMin() (with tied minima only that one counts). progress(done_rows, rows) is
// called once per surface row when given. Throws std::invalid_argument for invalid options or
// a surface that is not a square CV_64FC1 matrix of side 2R + 1 with at least one valid cell.
SuccessRateMap ComputeSuccessRateMap(const ErrorSurface& surface, const DescentOptions& options,
                                     const std::function<void(int, int)>& progress = nullptr);

// Thesis Table 3.2 compared static and random sampling at very different pixel counts:
// 14,600 sampled pixels for static, 2,500 for random (the project's own default, a 100×100
// patch, gives 1,816 and 1,000). To reproduce the table, both patterns sit on the same square
// patch, the smallest whose static pattern reaches 14,600 pixels (284×284: 14,663; 283×283
// gives 14,561), and random draws exactly 2,500 of its pixels.
inline constexpr int kThesisStaticPixels = 14600;
inline constexpr int kThesisRandomPixels = 2500;

struct ThesisSurfaceSampling {
  int patch_side = 0;  // [px] side of the square patch
  SamplingOptions sampling;
  int sampled_pixels = 0;  // what the pattern really holds
};

// kind must be kStatic or kRandom (std::invalid_argument otherwise).
ThesisSurfaceSampling ThesisTable32Sampling(SamplingKind kind, std::uint32_t seed);

}  // namespace kapfix
