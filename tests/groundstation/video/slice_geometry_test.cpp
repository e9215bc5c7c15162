#include "groundstation/video/slice_geometry.hpp"

#include <gtest/gtest.h>

namespace kapfix::station {
namespace {

TEST(SliceGeometry, RowsMapToSlicesNumberedFromTheTop) {
  EXPECT_EQ(SliceAt(0, 900, 9), 1U);
  EXPECT_EQ(SliceAt(99.9, 900, 9), 1U);
  EXPECT_EQ(SliceAt(100, 900, 9), 2U);
  EXPECT_EQ(SliceAt(899, 900, 9), 9U);
}

TEST(SliceGeometry, RowsOutsideTheFrameOrNoSlicesMeanNone) {
  EXPECT_EQ(SliceAt(-1, 900, 9), 0U);
  EXPECT_EQ(SliceAt(900, 900, 9), 0U);
  EXPECT_EQ(SliceAt(10, 900, 0), 0U);
}

TEST(SliceGeometry, BandOfASliceIsItsShareOfTheHeight) {
  const QRectF band = SliceBand(3, 9, 300, 900);
  EXPECT_DOUBLE_EQ(band.top(), 200);
  EXPECT_DOUBLE_EQ(band.height(), 100);
  EXPECT_DOUBLE_EQ(band.width(), 300);
  EXPECT_TRUE(SliceBand(10, 9, 300, 900).isNull());
}

}  // namespace
}  // namespace kapfix::station
