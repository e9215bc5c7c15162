#include "bench/loop_parallel_flights.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <system_error>
#include <thread>
#include <vector>

namespace kapfix::bench {

void FlyInParallel(std::size_t count, int jobs, const std::function<void(std::size_t)>& fly,
                   const std::function<void(std::size_t)>& done) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::mutex mutex;  // guards done() and the failure below
  std::exception_ptr failure;
  std::size_t failed_index = count;
  const auto work = [&] {
    for (std::size_t k = next++; k < count && !failed; k = next++) {
      try {
        fly(k);
        const std::lock_guard<std::mutex> lock(mutex);
        done(k);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        failed = true;
        if (k < failed_index) {
          failed_index = k;
          failure = std::current_exception();
        }
      }
    }
  };
  const std::size_t threads = std::min<std::size_t>(static_cast<std::size_t>(std::max(1, jobs)),
                                                    std::max<std::size_t>(1, count));
  std::vector<std::thread> pool;
  try {
    for (std::size_t t = 1; t < threads; ++t) pool.emplace_back(work);
  } catch (const std::system_error&) {
    // No more threads to be had: the ones started and this one fly everything.
  }
  work();  // the calling thread is one of the jobs
  for (std::thread& thread : pool) thread.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace kapfix::bench
