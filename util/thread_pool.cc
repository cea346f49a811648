#include "util/thread_pool.h"

#include <algorithm>
#include <atomic>

namespace attend {

ThreadPool::ThreadPool(int workers) {
  threads_.reserve(workers > 0 ? workers : 0);
  for (int i = 0; i < workers; ++i) threads_.emplace_back([this] { Work(); });
}

ThreadPool::~ThreadPool() {
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  changed_.notify_all();
  for (std::thread& thread : threads_) thread.join();
}

void ThreadPool::Work() {
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    changed_.wait(lock, [this] { return quit_ || !queue_.empty(); });
    // The jobs handed out before the end still run: their futures are waited on.
    if (queue_.empty()) return;
    std::function<void()> job = std::move(queue_.front());
    queue_.pop_front();
    lock.unlock();
    job();
    lock.lock();
  }
}

std::future<void> ThreadPool::Submit(std::function<void()> job) {
  auto task = std::make_shared<std::packaged_task<void()>>(std::move(job));
  std::future<void> done = task->get_future();
  if (threads_.empty()) {
    (*task)();
    return done;
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    queue_.emplace_back([task] { (*task)(); });
  }
  changed_.notify_one();
  return done;
}

namespace {

// The tasks of one ParallelFor: whoever takes part takes the next index until none is left.
// Shared, so that a worker that gets to it after the call has returned finds it empty.
struct Loop {
  explicit Loop(int count, const std::function<void(int)>* task) : count(count), task(task) {}
  const int count;
  const std::function<void(int)>* task;  // valid while some index is not yet done
  std::atomic<int> next{0};
  std::mutex mutex;
  std::condition_variable finished;
  int done = 0;  // guarded by mutex

  // Runs indices until none is left to take.
  void TakePart() {
    int ran = 0;
    for (int i = next.fetch_add(1); i < count; i = next.fetch_add(1)) {
      (*task)(i);
      ++ran;
    }
    if (ran == 0) return;
    const std::lock_guard<std::mutex> lock(mutex);
    done += ran;
    if (done == count) finished.notify_all();
  }
};

}  // namespace

void ThreadPool::ParallelFor(int count, const std::function<void(int)>& task) {
  if (count <= 0) return;
  if (threads_.empty() || count == 1) {
    for (int i = 0; i < count; ++i) task(i);
    return;
  }
  auto loop = std::make_shared<Loop>(count, &task);
  const int helpers = std::min(count - 1, workers());
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (int i = 0; i < helpers; ++i) queue_.emplace_back([loop] { loop->TakePart(); });
  }
  changed_.notify_all();
  loop->TakePart();
  std::unique_lock<std::mutex> lock(loop->mutex);
  loop->finished.wait(lock, [&] { return loop->done == count; });
}

}  // namespace attend
