#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/control/calibration.hpp"
#include "common/selection/patch_size_selection.hpp"
#include "common/selection/slice_selection.hpp"
#include "kapfix/v1/calibration.pb.h"
#include "kapfix/v1/slices.pb.h"

namespace kapfix::agent {

// The selection and calibration results as kapfix.v1 messages (headers are stamped by the
// publisher).
struct SwingProgress {
  int done = 0;   // [frames] of the free swing processed
  int total = 0;  // [frames] planned
  bool finished = false;
  bool deadline_reached = false;  // stopped by the time limit before the planned frames
};

struct SliceReportContext {
  SliceScoreKind score = SliceScoreKind::kDc;
  double hysteresis_px = 1.5;  // [px]
  int patch_size_px = 100;     // [px]
  std::string strategy;
};

// The ranking score of SSP as kapfix.v1 names it (reports and the agent's settings).
kapfix::v1::SliceScoreKind ToProto(SliceScoreKind kind);

kapfix::v1::SliceReport MakeSliceReport(const SliceSelection& selection,
                                        const SliceReportContext& context,
                                        const SwingProgress& progress);

kapfix::v1::PssReport MakePssReport(const PatchSizeSelection& selection,
                                    const std::vector<std::vector<double>>& graphs,
                                    const SwingProgress& progress);

// `pan`/`tilt`: the fits, absent while running or when the fit failed (valid = false).
kapfix::v1::CalibrationReport MakeCalibrationReport(const std::string& lens_profile,
                                                    const std::optional<AxisCalibration>& pan,
                                                    const std::optional<AxisCalibration>& tilt,
                                                    int moves_done, int moves_total, bool finished);

}  // namespace kapfix::agent
