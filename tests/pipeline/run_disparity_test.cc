// The run's disparity (FrameContext::disparity_options): the `disparity` feature's entry sets
// the options plugins find in the context; without that feature they are the defaults.
#include <gtest/gtest.h>

#include "features/builtin.h"
#include "pipeline/frame_pipeline.h"
#include "tests/support/pipeline_options.h"

namespace attend {
namespace {

using testing::WithFeatures;

FeatureSetup StereoSetup() { return testing::SetupFor(true); }

// The tests' execution context (util/execution_context.h): one thread.
ExecutionContext* DisparityRunExecution() {
  static ExecutionContext execution(1);
  return &execution;
}

TEST(RunDisparity, TheDisparityFeaturesEntryChoosesTheContextsOptions) {
  const FramePipeline pipeline(
      WithFeatures("[{name: intensity_contrast}, {name: disparity, max_disparity: 24, window: "
                   "9, smoothness: penalty}]"),
      BuiltinFeatures(), StereoSetup(), DisparityRunExecution());
  const DisparityOptions& options = pipeline.context().disparity_options();
  EXPECT_EQ(options.max_disparity, 24);
  EXPECT_EQ(options.window, 9);
  EXPECT_EQ(options.smoothness, DisparitySmoothness::kPenalty);
}

TEST(RunDisparity, WithoutTheFeatureOrWithItDisabledTheOptionsAreTheDefaults) {
  for (const std::string& features :
       {std::string("[{name: intensity_contrast}]"),
        std::string(
            "[{name: intensity_contrast}, {name: disparity, window: 9, enabled: false}]")}) {
    const FramePipeline pipeline(WithFeatures(features), BuiltinFeatures(), StereoSetup(),
                                 DisparityRunExecution());
    EXPECT_TRUE(pipeline.context().disparity_options() == DisparityOptions()) << features;
  }
}

}  // namespace
}  // namespace attend
