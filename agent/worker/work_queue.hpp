#pragma once

#include <condition_variable>
#include <cstddef>
#include <deque>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace kapfix::agent {

// A thread of its own that runs slow jobs (a disk write with fsync, a device to reopen) one at
// a time and in order, so that the thread that posts them (the control thread) never waits for
// them. Bounded: a job posted while `max_jobs` are waiting is refused with the reason, never
// dropped silently. A job returns its result as a function, which runs on the thread that
// calls Deliver() (the control thread, between frames): results come back there as events, in
// the order the jobs ran.
class WorkQueue {
 public:
  using Result = std::function<void()>;
  using Job = std::function<Result()>;

  // `name` names the queue in refusals and logs ("photo writer"); `max_jobs` ≥ 1.
  WorkQueue(std::string name, std::size_t max_jobs);
  ~WorkQueue();  // runs the jobs already posted, then ends the thread (results not delivered)
  WorkQueue(const WorkQueue&) = delete;
  WorkQueue& operator=(const WorkQueue&) = delete;

  // Any thread; never waits for a job. False (and why, naming `what`) when the queue is full
  // or stopping. A job that throws is logged; its result is then none.
  bool Post(const std::string& what, Job job, std::string* error);
  // Runs the results of the jobs done since the last call, oldest first, on the caller's
  // thread; waits for no job. Returns how many ran.
  std::size_t Deliver();
  // Any thread: waits until every job posted so far has run (shutdown, tests).
  void Flush();

  std::size_t waiting() const;  // jobs posted and not yet run

 private:
  void Run();

  const std::string name_;
  const std::size_t max_jobs_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  std::condition_variable drained_;
  std::deque<std::pair<std::string, Job>> jobs_;
  std::deque<Result> results_;
  bool running_job_ = false;
  bool stop_ = false;
  std::thread thread_;  // last: started when everything else is ready
};

}  // namespace kapfix::agent
