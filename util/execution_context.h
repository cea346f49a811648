// What the stages of one run (or of one Python object) share, made by the caller and passed
// down, rather than set for the whole process (as Ceres' include/ceres/context.h): the number
// of threads and the threads themselves, and the pools of buffers that objects built one after
// another lend each other (the pyramids' BipPool, pyramid/bip.h). `attend run` makes one for the run
// (pipeline/run.cc), the Python module one per Pipeline (python/pipeline_bindings.cc);
// FramePipeline hands its parts the pools they use.
#pragma once

#include <memory>
#include <mutex>
#include <typeindex>
#include <utility>
#include <vector>

#include "util/thread_pool.h"

namespace attend {

class ExecutionContext {
 public:
  // `threads`: the threads the stages of a frame may share; 0: one per core.
  explicit ExecutionContext(int threads);
  ExecutionContext(const ExecutionContext&) = delete;
  ExecutionContext& operator=(const ExecutionContext&) = delete;

  // The threads asked for, 0 for one per core.
  int asked_threads() const { return asked_threads_; }
  // The threads to use: as asked, or the number of cores (at least 1).
  int threads() const { return threads_; }

  // The context's threads: threads() - 1 workers beside the caller's thread, started on first
  // use and joined when the context ends. The stages of a frame share them (RunTasks), and
  // `attend run` works on the next frame on one while it finishes the current one.
  ThreadPool* pool();

  // The context's one T (default-constructed on first use), for every part that is handed it:
  // e.g. Shared<BipPool>(), the pyramids' buffers. Thread-safe; lives as long as the context.
  template <typename T>
  T* Shared() {
    const std::lock_guard<std::mutex> lock(mutex_);
    for (const auto& [type, shared] : shared_) {
      if (type == std::type_index(typeid(T))) return static_cast<T*>(shared.get());
    }
    shared_.emplace_back(std::type_index(typeid(T)), std::make_shared<T>());
    return static_cast<T*>(shared_.back().second.get());
  }

 private:
  int asked_threads_;
  int threads_;
  std::mutex mutex_;
  // shared_ptr<void> keeps each T's own deleter.
  std::vector<std::pair<std::type_index, std::shared_ptr<void>>> shared_;
  // Last: its workers are joined before the shared objects they may use go.
  std::unique_ptr<ThreadPool> pool_;
};

// The one place where attend limits OpenCV's own parallelism (cv::parallel_for_, which the
// stages of a frame run on, and OpenCV's functions themselves): while it lives, OpenCV uses
// the threads `context` asked for; the previous number is restored at its end. Nothing when
// the context asked for one per core (OpenCV's default). OpenCV's setting is the process's, so
// objects of this kind alive at once in several threads should ask for the same number.
class ScopedOpenCvThreads {
 public:
  explicit ScopedOpenCvThreads(const ExecutionContext& context);
  ~ScopedOpenCvThreads();
  ScopedOpenCvThreads(const ScopedOpenCvThreads&) = delete;
  ScopedOpenCvThreads& operator=(const ScopedOpenCvThreads&) = delete;

 private:
  int previous_ = -1;  // -1: nothing to restore
};

}  // namespace attend
