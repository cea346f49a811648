#include "util/execution_context.h"

#include <algorithm>
#include <opencv2/core/utility.hpp>
#include <thread>

namespace attend {

ExecutionContext::ExecutionContext(int threads)
    : asked_threads_(threads),
      threads_(threads > 0 ? threads
                           : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()))) {}

ScopedOpenCvThreads::ScopedOpenCvThreads(const ExecutionContext& context) {
  if (context.asked_threads() <= 0) return;
  previous_ = cv::getNumThreads();
  cv::setNumThreads(context.asked_threads());
}

ScopedOpenCvThreads::~ScopedOpenCvThreads() {
  if (previous_ >= 0) cv::setNumThreads(previous_);
}

}  // namespace attend
