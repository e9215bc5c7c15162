#pragma once

#include <opencv2/core.hpp>

namespace kapfix {

// The two filters strategy "pyr" runs on every current frame, for 8-bit planes bit for bit
// what OpenCV computes, in one pass each. On the small crops pyr reduces (300×132 pixels at
// 300×300 frames) OpenCV's per-call set-up (filter engines, border tables, row buffers) cost
// more than the arithmetic; these keep their row buffers from call to call and vectorise the
// [1 4 6 4 1] passes in 16-bit lanes (the sums stay below 2¹⁶). Other depths, and planes
// smaller than the 5-pixel kernel, go to OpenCV.

// cv::pyrDown(src, dst): Gaussian [1 4 6 4 1]ᵀ[1 4 6 4 1] / 256, BORDER_REFLECT_101, every
// second pixel, dst of ((cols + 1) / 2) × ((rows + 1) / 2). dst must not share src's data; it
// keeps its buffer when it already has the right size and type.
void PyrDown(const cv::Mat& src, cv::Mat& dst);

// The band-pass of pyr's coarse level: dst = src − blur(src) + 128, saturated, where blur is
// cv::GaussianBlur(src, blur, {5, 5}, 0, 0, cv::BORDER_REPLICATE | cv::BORDER_ISOLATED), i.e.
// what cv::addWeighted(src, 1, blur, −1, 128, dst) gives. dst must not share src's data.
void BandPass(const cv::Mat& src, cv::Mat& dst);

}  // namespace kapfix
