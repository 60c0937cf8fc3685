#pragma once
// A fixed set of worker threads that run submitted jobs and hand back their results as futures.

#include <condition_variable>
#include <deque>
#include <functional>
#include <future>
#include <mutex>
#include <thread>
#include <type_traits>
#include <utility>
#include <vector>

namespace freeplay {

/// Runs jobs on `threads` worker threads (jobs start in submission order); the destructor finishes every queued job.
class TaskPool {
 public:
  /// A pool of `threads` workers; 0 runs every job at once on the submitting thread.
  explicit TaskPool(int threads);
  /// Runs what is still queued, then joins the workers.
  ~TaskPool();
  TaskPool(const TaskPool&) = delete;
  TaskPool& operator=(const TaskPool&) = delete;

  /// Queues `job`; its result (or exception) arrives through the future.
  template <class Job>
  std::future<std::invoke_result_t<Job>> submit(Job job) {
    using Result = std::invoke_result_t<Job>;
    auto task = std::make_shared<std::packaged_task<Result()>>(std::move(job));
    auto future = task->get_future();
    if (workers_.empty()) {
      (*task)();
    } else {
      enqueue([task] { (*task)(); });
    }
    return future;
  }

  /// Worker threads (0: jobs run on the submitting thread).
  int threads() const { return static_cast<int>(workers_.size()); }

 private:
  void enqueue(std::function<void()> job);
  void work();

  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<std::function<void()>> queue_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace freeplay
