#pragma once

// Whether a photo is fit to keep (issue 13), from the quality the agent measured at capture
// (PhotoMetadata 13–24): blurred when the view moved too far during the exposure, off target
// when it was too far from the reference or the lock was not trusted. Qt-free, so the
// thresholds are tested without a window.

#include <string>

#include "kapfix/v1/photo.pb.h"

namespace kapfix::station {

// [px] view travel during the exposure above which a photo is blurred: beyond one pixel the
// smear of a point covers more than two pixels and is visible at full size.
inline constexpr double kBlurredPx = 1.0;
// [px] distance of the view from the reference above which a photo is off target: the
// residual graph's fixed ±10 px scale, a tenth of the thesis' 100 px patch, beyond which the
// framing the operator chose has visibly moved.
inline constexpr double kOffTargetPx = 10.0;

struct PhotoJudgement {
  bool measured = false;    // the agent measured the quality (an older one does not)
  bool blurred = false;     // view_blur_px > kBlurredPx
  bool off_target = false;  // residual_offset_px > kOffTargetPx, or the lock was lost
  // "BLURRED (1.8 px during the exposure), OFF TARGET (lock lost)"; empty when neither.
  std::string flags;
};

PhotoJudgement JudgePhoto(const kapfix::v1::PhotoMetadata& metadata);

}  // namespace kapfix::station
