#include "groundstation/photos/photo_quality.hpp"

#include <cstdio>

namespace kapfix::station {
namespace {

std::string Px(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f px", value);
  return text;
}

}  // namespace

PhotoJudgement JudgePhoto(const kapfix::v1::PhotoMetadata& metadata) {
  PhotoJudgement judgement;
  // The shutter mode is set on every photo an agent with quality figures takes.
  judgement.measured = metadata.shutter() != kapfix::v1::SHUTTER_UNSPECIFIED;
  if (!judgement.measured) return judgement;
  const double blur_px = metadata.view_blur_px();
  const double offset_px = metadata.residual_offset_px();
  judgement.blurred = blur_px > kBlurredPx;
  judgement.off_target = metadata.lock_lost() || offset_px > kOffTargetPx;
  if (judgement.blurred) judgement.flags = "BLURRED (" + Px(blur_px) + " during the exposure)";
  if (judgement.off_target) {
    if (!judgement.flags.empty()) judgement.flags += ", ";
    judgement.flags += "OFF TARGET (";
    judgement.flags += metadata.lock_lost() ? "lock lost" : Px(offset_px) + " from the reference";
    judgement.flags += ")";
  }
  return judgement;
}

}  // namespace kapfix::station
