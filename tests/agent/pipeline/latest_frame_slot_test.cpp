#include "agent/pipeline/latest_frame_slot.hpp"

#include <gtest/gtest.h>

#include <thread>

namespace kapfix::agent {
namespace {

CapturedFrame Frame(std::uint64_t index) {
  CapturedFrame f;
  f.index = index;
  f.image = cv::Mat(4, 4, CV_8UC3, cv::Scalar::all(static_cast<double>(index)));
  return f;
}

TEST(LatestFrameSlotTest, KeepsOnlyTheLatestFrameAndCountsTheStaleOnes) {
  LatestFrameSlot slot;
  slot.Put(Frame(0));
  slot.Put(Frame(1));
  slot.Put(Frame(2));
  const auto taken = slot.Take();
  ASSERT_TRUE(taken.has_value());
  EXPECT_EQ(taken->index, 2u);
  EXPECT_EQ(slot.dropped(), 2u);
  EXPECT_EQ(slot.delivered(), 1u);
  // A frame taken in time is not a drop.
  slot.Put(Frame(3));
  EXPECT_EQ(slot.Take()->index, 3u);
  EXPECT_EQ(slot.dropped(), 2u);
}

TEST(LatestFrameSlotTest, CloseHandsOutTheLastFrameThenEnds) {
  LatestFrameSlot slot;
  slot.Put(Frame(7));
  slot.Close();
  EXPECT_EQ(slot.Take()->index, 7u);
  EXPECT_FALSE(slot.Take().has_value());
  slot.Put(Frame(8));  // ignored after Close
  EXPECT_FALSE(slot.Take().has_value());
}

TEST(LatestFrameSlotTest, TakeWaitsForAProducerOnAnotherThread) {
  LatestFrameSlot slot;
  std::thread producer([&slot] {
    for (std::uint64_t i = 0; i < 3; ++i) {
      slot.Put(Frame(i));
      ASSERT_TRUE(slot.WaitDone(i));  // lock-step: nothing is dropped
    }
    slot.Close();
  });
  std::uint64_t expected = 0;
  while (auto frame = slot.Take()) {
    EXPECT_EQ(frame->index, expected++);
    slot.MarkDone(frame->index);
  }
  producer.join();
  EXPECT_EQ(expected, 3u);
  EXPECT_EQ(slot.dropped(), 0u);
}

}  // namespace
}  // namespace kapfix::agent
