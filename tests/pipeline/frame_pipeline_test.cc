// The pipeline takes its threads and its pools from the caller's execution context
// (util/execution_context.h) rather than from the process.
#include "pipeline/frame_pipeline.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "features/builtin.h"
#include "pyramid/bip.h"
#include "tests/support/pipeline_options.h"

namespace attend {
namespace {

StereoFrame Frame(int index) {
  StereoFrame frame;
  frame.index = index;
  frame.left = cv::Mat(60, 80, CV_8UC3, cv::Scalar(90, 90, 90));
  cv::rectangle(frame.left, cv::Rect(10 + index, 8, 20, 16), cv::Scalar(40, 40, 220), cv::FILLED);
  cv::rectangle(frame.left, cv::Rect(44, 30, 18, 20), cv::Scalar(200, 120, 40), cv::FILLED);
  return frame;
}

// Every pyramid of a frame (the segmentation's, the saliency segmentation's, the tracker's)
// borrows from the context's BipPool and gives its buffers back to it; two contexts keep
// theirs apart.
TEST(FramePipeline, ThePyramidsBorrowFromTheContextsPool) {
  const AttendOptions options =
      testing::WithFeatures("[{name: colour_contrast}, {name: intensity_contrast}]");
  ExecutionContext execution(1), other(1);
  FramePipeline pipeline(options, BuiltinFeatures(), testing::SetupFor(false), &execution);
  const BipPool& pool = *execution.Shared<BipPool>();
  EXPECT_EQ(pool.IdleScratches(), 0);
  for (int i = 0; i < 3; ++i) {
    FrameRecord record;
    pipeline.Process(Frame(i), &record);
  }
  // One thread: the builds ran one after another on one scratch, and the frame's levels were
  // given back (a tracker's are released at the end of its frame).
  EXPECT_EQ(pool.IdleScratches(), 1);
  EXPECT_GE(pool.IdleLevelSets(), 1);
  EXPECT_EQ(other.Shared<BipPool>()->IdleScratches(), 0);
}

// The threads are the context's, whatever the options say: one thread or two give one record.
TEST(FramePipeline, OneThreadOrTwoGiveTheSameRecords) {
  const AttendOptions options =
      testing::WithFeatures("[{name: colour_contrast}, {name: intensity_contrast}]");
  ExecutionContext one(1), two(2);
  FramePipeline serial(options, BuiltinFeatures(), testing::SetupFor(false), &one);
  FramePipeline parallel(options, BuiltinFeatures(), testing::SetupFor(false), &two);
  for (int i = 0; i < 3; ++i) {
    FrameRecord a, b;
    serial.Process(Frame(i), &a);
    parallel.Process(Frame(i), &b);
    EXPECT_EQ(cv::norm(serial.saliency(), parallel.saliency(), cv::NORM_INF), 0.0) << i;
    ASSERT_EQ(a.targets.size(), b.targets.size()) << i;
    for (size_t t = 0; t < a.targets.size(); ++t) {
      EXPECT_EQ(a.targets[t].id, b.targets[t].id);
      EXPECT_EQ(a.targets[t].bbox, b.targets[t].bbox);
    }
  }
}

}  // namespace
}  // namespace attend
