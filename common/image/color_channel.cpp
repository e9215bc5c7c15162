#include "common/image/color_channel.hpp"

#include <opencv2/core.hpp>
#include <stdexcept>
#include <vector>

namespace kapfix {

cv::Mat ExtractChannel(const cv::Mat& frame, ColorChannel channel) {
  if (frame.empty()) throw std::invalid_argument("ExtractChannel: empty frame");
  if (frame.depth() != CV_8U || (frame.channels() != 1 && frame.channels() != 3)) {
    throw std::invalid_argument("ExtractChannel: expected an 8-bit grey or BGR frame");
  }
  if (channel == ColorChannel::kGreen) {
    if (frame.channels() == 1) return frame;
    cv::Mat green;
    cv::extractChannel(frame, green, 1);
    return green;
  }
  if (channel == ColorChannel::kRgb) {
    if (frame.channels() == 3) return frame;
    cv::Mat bgr;
    cv::merge(std::vector<cv::Mat>{frame, frame, frame}, bgr);
    return bgr;
  }
  cv::Mat sum;
  if (frame.channels() == 1) {
    frame.convertTo(sum, CV_16U, 3.0);
    return sum;
  }
  cv::Mat planes[3];
  cv::split(frame, planes);
  cv::Mat acc;
  planes[0].convertTo(sum, CV_16U);
  planes[1].convertTo(acc, CV_16U);
  sum += acc;
  planes[2].convertTo(acc, CV_16U);
  sum += acc;
  return sum;
}

std::optional<ColorChannel> ParseColorChannel(std::string_view text) {
  if (text == "green") return ColorChannel::kGreen;
  if (text == "rgb") return ColorChannel::kRgb;
  if (text == "rgb-sum") return ColorChannel::kRgbSum;
  return std::nullopt;
}

std::string_view ToString(ColorChannel channel) {
  switch (channel) {
    case ColorChannel::kGreen:
      return "green";
    case ColorChannel::kRgbSum:
      return "rgb-sum";
    case ColorChannel::kRgb:
      return "rgb";
  }
  return "green";
}

}  // namespace kapfix
