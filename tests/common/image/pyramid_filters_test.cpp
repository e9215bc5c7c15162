#include "common/image/pyramid_filters.hpp"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "common/image/color_channel.hpp"
#include "tests/support/test_images.hpp"

namespace kapfix {
namespace {

cv::Mat Noise(cv::Size size, int seed) {
  cv::Mat m(size, CV_8UC1);
  cv::RNG rng(static_cast<std::uint64_t>(seed));
  rng.fill(m, cv::RNG::UNIFORM, 0, 256);
  return m;
}

// Test planes: full-range noise (every rounding case, sums near 2¹⁶) at even, odd and tiny
// sizes, an ROI with its own stride, and a photo's green plane at the size pyr reduces.
std::vector<cv::Mat> Planes() {
  std::vector<cv::Mat> planes;
  for (const cv::Size size : {cv::Size(300, 132), cv::Size(75, 33), cv::Size(76, 34),
                              cv::Size(3, 3), cv::Size(4, 7), cv::Size(17, 5)}) {
    planes.push_back(Noise(size, size.area()));
  }
  static const cv::Mat parent = Noise({200, 150}, 9);
  planes.push_back(parent(cv::Rect(13, 21, 120, 64)));
  const cv::Mat photo = ExtractChannel(testing::LoadOpenCvPhoto("aero1.jpg"), ColorChannel::kGreen);
  planes.push_back(photo(cv::Rect(96, 84, 300, 132)));
  return planes;
}

void ExpectIdentical(const cv::Mat& ours, const cv::Mat& opencv, const cv::Size& from) {
  ASSERT_EQ(ours.size(), opencv.size()) << "from " << from;
  ASSERT_EQ(ours.type(), opencv.type()) << "from " << from;
  EXPECT_EQ(cv::norm(ours, opencv, cv::NORM_INF), 0.0) << "from " << from;
}

TEST(PyramidFiltersTest, PyrDownEqualsOpenCvBitForBit) {
  for (const cv::Mat& plane : Planes()) {
    cv::Mat ours;
    cv::Mat opencv;
    PyrDown(plane, ours);
    cv::pyrDown(plane, opencv);
    ExpectIdentical(ours, opencv, plane.size());
  }
}

TEST(PyramidFiltersTest, BandPassEqualsOpenCvBlurAndSubtractBitForBit) {
  for (const cv::Mat& plane : Planes()) {
    cv::Mat ours;
    cv::Mat blurred;
    cv::Mat opencv;
    BandPass(plane, ours);
    // BORDER_ISOLATED: an ROI's edges are replicated, not read from its parent (pyr band-passes
    // whole levels, where the two agree).
    cv::GaussianBlur(plane, blurred, cv::Size(5, 5), 0.0, 0.0,
                     cv::BORDER_REPLICATE | cv::BORDER_ISOLATED);
    cv::addWeighted(plane, 1.0, blurred, -1.0, 128.0, opencv);
    ExpectIdentical(ours, opencv, plane.size());
  }
}

TEST(PyramidFiltersTest, KeepsAnOutputBufferOfTheRightSize) {
  // pyr reuses its thread-local level buffers: no allocation when the size holds.
  const cv::Mat plane = Noise({64, 48}, 3);
  cv::Mat out(24, 32, CV_8UC1);
  const std::uint8_t* buffer = out.data;
  PyrDown(plane, out);
  EXPECT_EQ(out.data, buffer);
  cv::Mat band(48, 64, CV_8UC1);
  const std::uint8_t* band_buffer = band.data;
  BandPass(plane, band);
  EXPECT_EQ(band.data, band_buffer);
}

TEST(PyramidFiltersTest, SixteenBitPlanesGoToOpenCv) {
  cv::Mat plane;
  Noise({40, 30}, 4).convertTo(plane, CV_16U, 3.0);
  cv::Mat ours;
  cv::Mat opencv;
  PyrDown(plane, ours);
  cv::pyrDown(plane, opencv);
  ExpectIdentical(ours, opencv, plane.size());
}

}  // namespace
}  // namespace kapfix
