// The threads of one run (or of one Python object), owned by its ExecutionContext
// (util/execution_context.h) rather than set for the whole process: the stages of a frame
// share them (RunTasks, features/feature_set.h), and `attend run` works on the next frame on
// one of them while it tracks and selects in the current one (pipeline/frame_pipeline.h).
#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <future>
#include <memory>
#include <mutex>
#include <thread>
#include <vector>

namespace attend {

class ThreadPool {
 public:
  // `workers` threads besides the callers' (0: every call runs on the calling thread).
  explicit ThreadPool(int workers);
  ~ThreadPool();  // waits for the jobs already handed to the workers
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  int workers() const { return static_cast<int>(threads_.size()); }

  // Runs task(0) .. task(count - 1) and returns when all have run. The calling thread takes
  // part, so a call from one of the pool's own workers, or while every worker is busy, never
  // waits for a free worker: it runs the tasks itself. Exceptions are the caller's business
  // (RunTasks keeps them); a task must not throw.
  void ParallelFor(int count, const std::function<void(int)>& task);

  // Runs `job` on a worker; the future gives its end and its exception. Without workers the
  // job runs at once, on this thread, and the future is ready.
  std::future<void> Submit(std::function<void()> job);

 private:
  void Work();

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<std::function<void()>> queue_;
  bool quit_ = false;
  std::vector<std::thread> threads_;  // last: they start once the members above exist
};

}  // namespace attend
