#include "agent/worker/work_queue.hpp"

#include <spdlog/spdlog.h>

#include <stdexcept>
#include <utility>

namespace kapfix::agent {
namespace {

std::size_t CheckedMaxJobs(const std::string& name, std::size_t max_jobs) {
  if (max_jobs == 0) throw std::invalid_argument(name + ": max_jobs must be at least 1");
  return max_jobs;
}

}  // namespace

WorkQueue::WorkQueue(std::string name, std::size_t max_jobs)
    : name_(std::move(name)),
      max_jobs_(CheckedMaxJobs(name_, max_jobs)),
      thread_([this] { Run(); }) {}

WorkQueue::~WorkQueue() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
}

bool WorkQueue::Post(const std::string& what, Job job, std::string* error) {
  {
    std::lock_guard lock(mutex_);
    if (stop_ || jobs_.size() >= max_jobs_) {
      const std::string why = stop_ ? name_ + " is stopping: " + what + " refused"
                                    : name_ + " full (" + std::to_string(jobs_.size()) +
                                          " jobs waiting): " + what + " refused";
      if (error) *error = why;
      spdlog::error("{}", why);
      return false;
    }
    jobs_.emplace_back(what, std::move(job));
  }
  wake_.notify_one();
  return true;
}

std::size_t WorkQueue::Deliver() {
  std::deque<Result> results;
  {
    std::lock_guard lock(mutex_);
    std::swap(results, results_);
  }
  for (const Result& result : results) result();
  return results.size();
}

void WorkQueue::Flush() {
  std::unique_lock lock(mutex_);
  drained_.wait(lock, [this] { return jobs_.empty() && !running_job_; });
}

std::size_t WorkQueue::waiting() const {
  std::lock_guard lock(mutex_);
  return jobs_.size();
}

void WorkQueue::Run() {
  std::unique_lock lock(mutex_);
  while (true) {
    running_job_ = false;
    drained_.notify_all();
    wake_.wait(lock, [this] { return stop_ || !jobs_.empty(); });
    if (jobs_.empty()) return;  // stopping, nothing left to run
    auto [what, job] = std::move(jobs_.front());
    jobs_.pop_front();
    running_job_ = true;
    lock.unlock();
    Result result;
    try {
      result = job();
    } catch (const std::exception& e) {
      spdlog::error("{}: {} failed: {}", name_, what, e.what());
    }
    lock.lock();
    if (result) results_.push_back(std::move(result));
  }
}

}  // namespace kapfix::agent
