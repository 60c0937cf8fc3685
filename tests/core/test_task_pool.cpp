#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>
#include <vector>

#include "freeplay/core/error.hpp"
#include "freeplay/core/task_pool.hpp"

using freeplay::TaskPool;

TEST(TaskPool, EveryJobRunsAndHandsBackItsResult) {
  for (const int threads : {0, 1, 3}) {
    TaskPool pool(threads);
    EXPECT_EQ(pool.threads(), threads);
    std::vector<std::future<int>> results;
    for (int i = 0; i < 50; ++i) results.push_back(pool.submit([i] { return i * i; }));
    for (int i = 0; i < 50; ++i) EXPECT_EQ(results[static_cast<std::size_t>(i)].get(), i * i) << threads << " threads";
  }
}

TEST(TaskPool, ZeroThreadsRunJobsOnTheSubmittingThread) {
  TaskPool pool(0);
  const auto caller = std::this_thread::get_id();
  EXPECT_EQ(pool.submit([] { return std::this_thread::get_id(); }).get(), caller);
  TaskPool workers(2);
  EXPECT_NE(workers.submit([] { return std::this_thread::get_id(); }).get(), caller);
}

TEST(TaskPool, AJobsExceptionArrivesThroughItsFuture) {
  TaskPool pool(2);
  auto failing = pool.submit([]() -> int { throw std::runtime_error("bad frame"); });
  auto fine = pool.submit([] { return 1; });
  EXPECT_THROW(failing.get(), std::runtime_error);
  EXPECT_EQ(fine.get(), 1);
}

TEST(TaskPool, TheDestructorFinishesQueuedJobs) {
  std::atomic<int> done{0};
  {
    TaskPool pool(1);
    for (int i = 0; i < 20; ++i) {
      (void)pool.submit([&done] {
        std::this_thread::sleep_for(std::chrono::microseconds(100));
        ++done;
      });
    }
  }
  EXPECT_EQ(done.load(), 20);
}

TEST(TaskPool, NegativeThreadCountIsRefused) { EXPECT_THROW(TaskPool(-1), freeplay::InputError); }
