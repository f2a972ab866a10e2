#pragma once
// Independent pieces of work shared among threads. A comparison (comparison.hpp) runs each model's fit, then
// its two evidence computations (the priors as given and widened tenfold), then its posterior band:
// a handful of jobs of a second or more each, with nothing to share while they run. Threads that
// take whole jobs wait for each other only when the queue runs dry, where threads inside one
// sampler wait at every half-ensemble step (docs/performance.md, "Threads").
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace sedwave::inversion {

class JobQueue {
 public:
  /// A job may add follow-up jobs (work that needs its result) through the queue it is given.
  using Job = std::function<void(JobQueue&)>;

  /// Queues a job. Jobs added by a running job go first, ahead of every job still waiting: a
  /// model's evidence starts as soon as its fit is done, and the longest chains of work start early.
  void add(Job job) {
    const std::lock_guard lock(mutex_);
    if (running_ > 0) {
      jobs_.push_front(std::move(job));
    } else {
      jobs_.push_back(std::move(job));
    }
    ready_.notify_one();
  }

  /// Runs every job, and every job they add, on `threads` threads (>= 1; 1: in this thread, in
  /// order). Each job must write only its own results: the results are then the same for any
  /// thread count. After a job throws no further job starts, and the first exception is rethrown
  /// once the running ones have finished.
  void run(int threads) {
    if (threads <= 1) {
      work();
    } else {
      std::vector<std::jthread> workers;
      for (int t = 0; t < threads; ++t) workers.emplace_back([this] { work(); });
    }
    if (error_) std::rethrow_exception(error_);
  }

 private:
  void work() {
    std::unique_lock lock(mutex_);
    for (;;) {
      ready_.wait(lock, [this] { return !jobs_.empty() || running_ == 0 || error_; });
      if (jobs_.empty() || error_) {
        ready_.notify_all();  // nothing left, and nothing running that could add more
        return;
      }
      Job job = std::move(jobs_.front());
      jobs_.pop_front();
      ++running_;
      lock.unlock();
      std::exception_ptr failed;
      try {
        job(*this);
      } catch (...) {
        failed = std::current_exception();
      }
      lock.lock();
      --running_;
      if (failed && !error_) error_ = failed;
      ready_.notify_all();
    }
  }

  std::mutex mutex_;
  std::condition_variable ready_;
  std::deque<Job> jobs_;
  int running_ = 0;
  std::exception_ptr error_;
};

}  // namespace sedwave::inversion
