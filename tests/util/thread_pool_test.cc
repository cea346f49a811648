// The run's threads (util/thread_pool.h): every task runs once, a call from a busy worker does
// not wait for itself, and a job's exception reaches whoever waits for it.
#include "util/thread_pool.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <set>
#include <stdexcept>
#include <vector>

#include "util/execution_context.h"

namespace attend {
namespace {

TEST(ThreadPool, EveryIndexRunsExactlyOnce) {
  ThreadPool pool(3);
  for (int round = 0; round < 200; ++round) {
    const int count = 1 + round % 17;
    std::vector<std::atomic<int>> runs(count);
    pool.ParallelFor(count, [&](int i) { runs[i].fetch_add(1); });
    for (int i = 0; i < count; ++i) ASSERT_EQ(runs[i].load(), 1) << round << " " << i;
  }
}

TEST(ThreadPool, TheWorkersTakePart) {
  ThreadPool pool(1);
  std::mutex mutex;
  std::set<std::thread::id> ran_on;
  // Each task waits until two threads are in the loop at once (or a second has passed), so
  // the worker must have taken one.
  std::atomic<int> inside{0};
  pool.ParallelFor(2, [&](int) {
    ++inside;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(1);
    while (inside.load() < 2 && std::chrono::steady_clock::now() < until) {
    }
    const std::lock_guard<std::mutex> lock(mutex);
    ran_on.insert(std::this_thread::get_id());
  });
  EXPECT_EQ(ran_on.size(), 2u);
  EXPECT_EQ(inside.load(), 2);
}

// A worker busy with a job that itself runs a loop on the pool: the loop runs on the calling
// worker instead of waiting for a free one (one worker, so it would wait for ever).
TEST(ThreadPool, ALoopFromTheOnlyWorkerDoesNotWaitForItself) {
  ThreadPool pool(1);
  std::atomic<int> sum{0};
  std::future<void> job = pool.Submit([&] {
    pool.ParallelFor(50, [&](int i) { sum += i; });
  });
  ASSERT_EQ(job.wait_for(std::chrono::seconds(20)), std::future_status::ready);
  job.get();
  EXPECT_EQ(sum.load(), 49 * 50 / 2);
}

TEST(ThreadPool, AJobsExceptionReachesItsFuture) {
  ThreadPool pool(1);
  std::future<void> job = pool.Submit([] { throw std::runtime_error("frame 7 is broken"); });
  try {
    job.get();
    FAIL() << "the job's exception was lost";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "frame 7 is broken");
  }
  // The worker is still there for the next job.
  int value = 0;
  pool.Submit([&] { value = 3; }).get();
  EXPECT_EQ(value, 3);
}

TEST(ThreadPool, WithoutWorkersEverythingRunsOnTheCaller) {
  ThreadPool pool(0);
  const std::thread::id caller = std::this_thread::get_id();
  std::thread::id ran_on;
  std::future<void> job = pool.Submit([&] { ran_on = std::this_thread::get_id(); });
  EXPECT_EQ(job.wait_for(std::chrono::seconds(0)), std::future_status::ready);
  EXPECT_EQ(ran_on, caller);
  std::vector<int> order;
  pool.ParallelFor(4, [&](int i) { order.push_back(i); });
  EXPECT_EQ(order, (std::vector<int>{0, 1, 2, 3}));
}

TEST(ThreadPool, TheEndWaitsForTheJobsHandedOut) {
  std::atomic<int> done{0};
  {
    ThreadPool pool(1);
    for (int i = 0; i < 5; ++i) {
      pool.Submit([&] {
        std::this_thread::sleep_for(std::chrono::milliseconds(5));
        ++done;
      });
    }
  }
  EXPECT_EQ(done.load(), 5);
}

// The pool is the context's: threads() - 1 workers, one pool for the context's life.
TEST(ThreadPool, TheContextOwnsOneWithOneWorkerFewerThanItsThreads) {
  ExecutionContext one(1), three(3);
  EXPECT_EQ(one.pool()->workers(), 0);
  EXPECT_EQ(three.pool()->workers(), 2);
  EXPECT_EQ(three.pool(), three.pool());
}

}  // namespace
}  // namespace attend
