#include "bench/loop_parallel_flights.hpp"

#include <gtest/gtest.h>

#include <condition_variable>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace kapfix::bench {
namespace {

// Flight k may return only once flight k + 1 is done: the flights finish last to first.
TEST(FlyInParallelTest, ResultsStayInIndexOrderWhileDoneFollowsTheFinishingOrder) {
  constexpr std::size_t kCount = 4;
  std::mutex mutex;
  std::condition_variable changed;
  std::vector<bool> reported(kCount + 1, false);
  reported[kCount] = true;
  std::vector<std::size_t> results(kCount, 0);
  std::vector<std::size_t> done_order;
  FlyInParallel(
      kCount, static_cast<int>(kCount),
      [&](std::size_t k) {
        std::unique_lock<std::mutex> lock(mutex);
        changed.wait(lock, [&] { return reported[k + 1]; });
        results[k] = 10 * k;
      },
      [&](std::size_t k) {
        const std::lock_guard<std::mutex> lock(mutex);
        done_order.push_back(k);
        reported[k] = true;
        changed.notify_all();
      });
  EXPECT_EQ(results, (std::vector<std::size_t>{0, 10, 20, 30}));
  EXPECT_EQ(done_order, (std::vector<std::size_t>{3, 2, 1, 0}));
}

TEST(FlyInParallelTest, OneJobFliesEveryFlightInOrderOnTheCallingThread) {
  std::vector<std::size_t> flown, done;
  const std::thread::id caller = std::this_thread::get_id();
  bool elsewhere = false;
  FlyInParallel(
      5, 1,
      [&](std::size_t k) {
        flown.push_back(k);
        elsewhere = elsewhere || std::this_thread::get_id() != caller;
      },
      [&](std::size_t k) { done.push_back(k); });
  EXPECT_EQ(flown, (std::vector<std::size_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(done, flown);
  EXPECT_FALSE(elsewhere);
}

TEST(FlyInParallelTest, AFailedFlightIsRethrownAndNoFurtherFlightStarts) {
  std::vector<std::size_t> flown, done;
  try {
    FlyInParallel(
        5, 1,
        [&](std::size_t k) {
          flown.push_back(k);
          if (k == 2) throw std::runtime_error("flight 2 failed");
        },
        [&](std::size_t k) { done.push_back(k); });
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "flight 2 failed");
  }
  EXPECT_EQ(flown, (std::vector<std::size_t>{0, 1, 2}));
  EXPECT_EQ(done, (std::vector<std::size_t>{0, 1}));
}

// Flight 1 fails first; flight 0, running beside it, fails after: flight 0's is rethrown.
TEST(FlyInParallelTest, TheLowestFailedFlightIsTheOneRethrown) {
  std::mutex mutex;
  std::condition_variable changed;
  bool one_failed = false;
  try {
    FlyInParallel(
        2, 2,
        [&](std::size_t k) {
          std::unique_lock<std::mutex> lock(mutex);
          if (k == 1) {
            one_failed = true;
            changed.notify_all();
            throw std::runtime_error("flight 1 failed");
          }
          changed.wait(lock, [&] { return one_failed; });
          throw std::runtime_error("flight 0 failed");
        },
        [](std::size_t) {});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "flight 0 failed");
  }
}

}  // namespace
}  // namespace kapfix::bench
