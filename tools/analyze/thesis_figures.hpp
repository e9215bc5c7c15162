#pragma once

#include <string>
#include <vector>

#include "common/control/calibration.hpp"

namespace kapfix::analyze {

// The thesis's published figures that `kapfix-analyze thesis` re-runs (SPEC §7 and the thesis
// text), kept verbatim in one place.

// Table 4.1: five calibration rounds, servo moves −100 … +100 in steps of 10, the pixel
// displacement each move gave (columns D1 … D5; 105 entries, five of them zero moves).
std::vector<CalibrationSample> ThesisTable41Samples();
inline constexpr double kThesisCalibration = 1.11;  // "Median(C1, …, C5) = 1.11"

// Table 3.2: success rates [%] of the descent controller, static vs random sampling.
struct ThesisSuccessRow {
  std::string image;      // the thesis's photo
  std::string our_photo;  // the opencv-doc photo standing in for it
  double static_pct = 0;  // 14,600 sampled pixels
  double random_pct = 0;  // 2,500 sampled pixels
};
const std::vector<ThesisSuccessRow>& ThesisTable32();

// Table 5.1: SSP's best and worst slice and their DC counts on ten lab images.
struct ThesisSliceRow {
  std::string image;
  std::string our_photo;  // the opencv-doc photo standing in for it
  int best_slice = 0;
  int best_dc = 0;
  int worst_slice = 0;
  int worst_dc = 0;
};
const std::vector<ThesisSliceRow>& ThesisTable51();

// The photos standing in for the five of chapter 4: Garden, Door, Flower, City, Street.
const std::vector<std::string>& ThesisStandInPhotos();

}  // namespace kapfix::analyze
