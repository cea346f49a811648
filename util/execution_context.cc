#include "util/execution_context.h"

#include <algorithm>
#include <opencv2/core/utility.hpp>
#include <thread>

namespace attend {

ExecutionContext::ExecutionContext(int threads)
    : asked_threads_(threads),
      threads_(threads > 0 ? threads
                           : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))) {}

ThreadPool* ExecutionContext::pool() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (pool_ == nullptr) pool_ = std::make_unique<ThreadPool>(threads_ - 1);
  return pool_.get();
}

ScopedOpenCvThreads::ScopedOpenCvThreads(const ExecutionContext& context) {
  if (context.asked_threads() <= 0) return;
  previous_ = cv::getNumThreads();
  cv::setNumThreads(context.asked_threads());
}

ScopedOpenCvThreads::~ScopedOpenCvThreads() {
  if (previous_ >= 0) cv::setNumThreads(previous_);
}

}  // namespace attend
