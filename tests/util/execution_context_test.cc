#include "util/execution_context.h"

#include <gtest/gtest.h>

#include <opencv2/core/utility.hpp>
#include <thread>

namespace attend {
namespace {

struct Counter {
  int count = 0;
};
struct Other {
  int count = 0;
};

TEST(ExecutionContext, ThreadsAreAsAskedOrOnePerCore) {
  EXPECT_EQ(ExecutionContext(3).threads(), 3);
  EXPECT_EQ(ExecutionContext(3).asked_threads(), 3);
  const ExecutionContext per_core(0);
  EXPECT_EQ(per_core.asked_threads(), 0);
  EXPECT_EQ(per_core.threads(),
            static_cast<int>(std::max(1u, std::thread::hardware_concurrency())));
}

// One T per context, the same each time it is asked; another context has its own.
TEST(ExecutionContext, SharedGivesTheContextsOneObjectOfEachType) {
  ExecutionContext context(1), other_context(1);
  Counter* counter = context.Shared<Counter>();
  counter->count = 7;
  EXPECT_EQ(context.Shared<Counter>(), counter);
  EXPECT_EQ(context.Shared<Counter>()->count, 7);
  EXPECT_EQ(context.Shared<Other>()->count, 0);
  EXPECT_NE(static_cast<void*>(context.Shared<Other>()), static_cast<void*>(counter));
  EXPECT_NE(other_context.Shared<Counter>(), counter);
  EXPECT_EQ(other_context.Shared<Counter>()->count, 0);
}

// OpenCV's thread count is the context's while the guard lives, and the previous one after.
TEST(ScopedOpenCvThreads, SetsOpenCvsThreadsForItsScopeOnly) {
  const int before = cv::getNumThreads();
  const int asked = before == 1 ? 2 : 1;
  {
    const ExecutionContext context(asked);
    const ScopedOpenCvThreads threads(context);
    EXPECT_EQ(cv::getNumThreads(), asked);
  }
  EXPECT_EQ(cv::getNumThreads(), before);
  {
    const ExecutionContext per_core(0);  // one per core: OpenCV's own choice, left alone
    const ScopedOpenCvThreads threads(per_core);
    EXPECT_EQ(cv::getNumThreads(), before);
  }
  EXPECT_EQ(cv::getNumThreads(), before);
}

}  // namespace
}  // namespace attend
