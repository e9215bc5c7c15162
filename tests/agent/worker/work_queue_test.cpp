// WorkQueue: slow jobs run on the queue's thread, in order; their results come back on the
// thread that delivers them; a full queue refuses a job and says why; nothing waits on a job.
#include "agent/worker/work_queue.hpp"

#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "tests/agent/support/gate.hpp"

namespace kapfix::agent {
namespace {

using kapfix::agent::testing::Gate;

TEST(WorkQueueTest, JobsRunInOrderOffTheCallersThreadAndResultsComeBackOnTheDeliveringThread) {
  WorkQueue queue("test queue", 8);
  std::vector<int> results;
  std::vector<std::thread::id> job_threads(3);
  std::vector<std::thread::id> result_threads;
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(queue.Post(
        "job " + std::to_string(i),
        [&, i]() -> WorkQueue::Result {
          job_threads[i] = std::this_thread::get_id();
          return [&, i] {
            results.push_back(i);
            result_threads.push_back(std::this_thread::get_id());
          };
        },
        nullptr));
  }
  queue.Flush();
  EXPECT_TRUE(results.empty());  // results wait for Deliver
  EXPECT_EQ(queue.Deliver(), 3u);
  EXPECT_EQ(results, (std::vector<int>{0, 1, 2}));
  for (const auto& id : job_threads) EXPECT_NE(id, std::this_thread::get_id());
  for (const auto& id : result_threads) EXPECT_EQ(id, std::this_thread::get_id());
}

TEST(WorkQueueTest, DeliverDoesNotWaitForAJobStillRunning) {
  WorkQueue queue("test queue", 2);
  Gate disk;
  bool delivered = false;
  ASSERT_TRUE(queue.Post(
      "slow write",
      [&]() -> WorkQueue::Result {
        disk.Pass();
        return [&] { delivered = true; };
      },
      nullptr));
  disk.WaitEntered();
  EXPECT_EQ(queue.Deliver(), 0u);  // returns while the job is blocked
  EXPECT_TRUE(disk.holding());
  disk.Open();
  queue.Flush();
  EXPECT_EQ(queue.Deliver(), 1u);
  EXPECT_TRUE(delivered);
}

TEST(WorkQueueTest, AFullQueueRefusesAJobWithTheReasonAndRunsEveryJobItTook) {
  constexpr std::size_t kMaxJobs = 3;
  WorkQueue queue("disk writer", kMaxJobs);
  Gate disk;
  int ran = 0;
  ASSERT_TRUE(queue.Post(
      "blocking",
      [&]() -> WorkQueue::Result {
        disk.Pass();
        return nullptr;
      },
      nullptr));
  disk.WaitEntered();  // the running job no longer counts as waiting
  for (std::size_t i = 0; i < kMaxJobs; ++i) {
    ASSERT_TRUE(queue.Post(
        "write",
        [&]() -> WorkQueue::Result {
          ++ran;
          return nullptr;
        },
        nullptr));
  }
  std::string error;
  EXPECT_FALSE(queue.Post(
      "photo 7",
      [&]() -> WorkQueue::Result {
        ++ran;
        return nullptr;
      },
      &error));
  EXPECT_NE(error.find("disk writer full"), std::string::npos) << error;
  EXPECT_NE(error.find("photo 7 refused"), std::string::npos) << error;
  disk.Open();
  queue.Flush();
  EXPECT_EQ(ran, static_cast<int>(kMaxJobs));
}

TEST(WorkQueueTest, AJobThatThrowsIsLoggedAndTheNextOneStillRuns) {
  WorkQueue queue("test queue", 4);
  bool next_ran = false;
  ASSERT_TRUE(queue.Post(
      "failing", []() -> WorkQueue::Result { throw std::runtime_error("disk full"); }, nullptr));
  ASSERT_TRUE(queue.Post(
      "next",
      [&]() -> WorkQueue::Result {
        next_ran = true;
        return nullptr;
      },
      nullptr));
  queue.Flush();
  EXPECT_TRUE(next_ran);
  EXPECT_EQ(queue.Deliver(), 0u);
}

TEST(WorkQueueTest, NoRoomForAnyJobIsRefusedAtConstruction) {
  EXPECT_THROW(WorkQueue("empty", 0), std::invalid_argument);
}

}  // namespace
}  // namespace kapfix::agent
