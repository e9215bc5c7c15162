#pragma once

#include <opencv2/core.hpp>

#include "common/shutter/best_phase_shutter.hpp"
#include "kapfix/v1/photo.pb.h"

namespace kapfix::agent {

// The shutter's part of a photo's quality (PhotoMetadata 13–19, 22, 23): offset, speed, blur
// and lock at capture, the mode, the wait and why, the exposure; the agent's camera took it.
void FillShotQuality(const ShutterShot& shot, kapfix::v1::PhotoMetadata* metadata);

// Sharpness of the photo (PhotoMetadata 20, 21): the variance of the Laplacian over the
// region where the reference patch is seen (`patch` in the reference frame, moved by the
// measured displacement; the whole frame's figure when there is no patch) and over the
// whole image.
void FillSharpness(const cv::Mat& image, cv::Rect patch, kapfix::v1::PhotoMetadata* metadata);

// Where the reference patch `patch` [px, reference frame] is seen in a frame whose measured
// displacement is `displacement` [px]: the content moved by the displacement.
cv::Rect PatchInFrame(cv::Rect patch, cv::Point2d displacement);

}  // namespace kapfix::agent
