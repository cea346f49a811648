// The pipeline takes its threads and its pools from the caller's execution context
// (util/execution_context.h) rather than from the process.
#include "pipeline/frame_pipeline.h"

#include <gtest/gtest.h>

#include <future>
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

// A feature that paints where attention looked in the frame before: its map, and so the
// saliency and the targets, depend on the attention stage's last frame. `claims_not` makes it
// say it does not read them, wrongly.
class LookedFeature final : public FeatureMap {
 public:
  explicit LookedFeature(bool claims_not) : claims_not_(claims_not) {}
  void Compute(const FrameContext& context, cv::Mat* out) override {
    out->create(context.size(), CV_32FC1);
    out->setTo(0.f);
    for (const cv::Rect& region : context.AttentionRegions()) {
      (*out)(region & cv::Rect(cv::Point(), context.size())).setTo(1.f);
    }
  }
  bool ReadsAttentionRegions() const override { return !claims_not_; }

 private:
  bool claims_not_;
};

FeatureRegistry RegistryWithLooked() {
  FeatureRegistry registry = BuiltinFeatures();
  registry.Add("looked", "paints where attention looked",
               [](const ParamBlock& params, const FeatureSetup&) {
                 return std::make_unique<LookedFeature>(params.GetBool("claims_not", false));
               });
  return registry;
}

StereoFrame Moving(int index) {
  StereoFrame frame;
  frame.index = index;
  frame.left = cv::Mat(120, 160, CV_8UC3, cv::Scalar(90, 90, 90));
  cv::rectangle(frame.left, cv::Rect(10 + 4 * index, 20, 30, 24), cv::Scalar(40, 40, 220),
                cv::FILLED);
  cv::rectangle(frame.left, cv::Rect(100, 70 - 2 * index, 24, 26), cv::Scalar(200, 120, 40),
                cv::FILLED);
  cv::circle(frame.left, cv::Point(60 + 3 * index, 90), 9, cv::Scalar(30, 200, 60), cv::FILLED);
  return frame;
}

struct FrameResult {
  FrameRecord record;
  cv::Mat saliency;
  cv::Mat inhibited;
  int feature_frame = -1;  // the frame index the pipeline's context holds
};

// `frames` frames through Process, one after the other.
std::vector<FrameResult> Processed(const std::string& features, int frames) {
  const AttendOptions options = testing::WithFeatures(features);
  ExecutionContext execution(1);
  FramePipeline pipeline(options, RegistryWithLooked(), testing::SetupFor(false), &execution);
  std::vector<FrameResult> results(frames);
  std::vector<StereoFrame> images;
  for (int i = 0; i < frames; ++i) images.push_back(Moving(i));
  for (int i = 0; i < frames; ++i) {
    pipeline.Process(images[i], &results[i].record);
    results[i].saliency = pipeline.saliency().clone();
    results[i].inhibited = pipeline.inhibited().clone();
    results[i].feature_frame = pipeline.context().frame_index();
  }
  return results;
}

// The same through Ahead and Finish as `attend run` with two threads calls them: Ahead of
// frame t + 1 on a worker while this thread finishes frame t.
std::vector<FrameResult> Overlapped(const std::string& features, int frames) {
  const AttendOptions options = testing::WithFeatures(features);
  ExecutionContext execution(2);
  FramePipeline pipeline(options, RegistryWithLooked(), testing::SetupFor(false), &execution);
  std::vector<StereoFrame> images;
  for (int i = 0; i < frames; ++i) images.push_back(Moving(i));
  std::vector<FrameResult> results(frames);
  pipeline.Ahead(images[0]);
  for (int i = 0; i < frames; ++i) {
    std::future<void> ahead;
    if (i + 1 < frames) {
      ahead = execution.pool()->Submit([&, i] { pipeline.Ahead(images[i + 1]); });
    }
    pipeline.Finish(&results[i].record);
    results[i].saliency = pipeline.saliency().clone();
    results[i].inhibited = pipeline.inhibited().clone();
    results[i].feature_frame = pipeline.context().frame_index();
    if (ahead.valid()) ahead.get();
  }
  return results;
}

// How many frames' targets or maps differ between `a` and `b`.
int FramesThatDiffer(const std::vector<FrameResult>& a, const std::vector<FrameResult>& b) {
  int differ = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    bool same = a[i].feature_frame == b[i].feature_frame &&
                cv::norm(a[i].saliency, b[i].saliency, cv::NORM_INF) == 0.0 &&
                cv::norm(a[i].inhibited, b[i].inhibited, cv::NORM_INF) == 0.0 &&
                a[i].record.targets.size() == b[i].record.targets.size() &&
                a[i].record.new_ids == b[i].record.new_ids;
    for (size_t t = 0; same && t < a[i].record.targets.size(); ++t) {
      same = a[i].record.targets[t].id == b[i].record.targets[t].id &&
             a[i].record.targets[t].bbox == b[i].record.targets[t].bbox &&
             a[i].record.targets[t].saliency == b[i].record.targets[t].saliency;
    }
    differ += same ? 0 : 1;
  }
  return differ;
}

// Frame t + 1's segmentation and features beside frame t's tracking and selection give the
// records, maps and accessors of one frame after the other; the feature that reads where
// attention looked waits for the frame before.
TEST(FramePipeline, AheadAndFinishGiveTheResultsOfProcess) {
  const std::string features =
      "[{name: colour_contrast}, {name: intensity_contrast}, {name: looked, weight: 2}]";
  const std::vector<FrameResult> serial = Processed(features, 12);
  const std::vector<FrameResult> overlapped = Overlapped(features, 12);
  EXPECT_EQ(FramesThatDiffer(serial, overlapped), 0);
  for (int i = 0; i < 12; ++i) EXPECT_EQ(overlapped[i].feature_frame, i);
  int targets = 0;
  for (const FrameResult& result : serial) targets += result.record.targets.size();
  EXPECT_GT(targets, 12);
}

// The test above can fail: a feature that reads where attention looked but says it does not
// runs ahead, on the regions of two frames before, and the results change.
TEST(FramePipeline, AFeatureThatHidesThatItReadsTheRegionsGetsOtherResults) {
  const std::string features =
      "[{name: colour_contrast}, {name: intensity_contrast}, "
      "{name: looked, weight: 2, claims_not: true}]";
  EXPECT_GT(FramesThatDiffer(Processed(features, 12), Overlapped(features, 12)), 0);
}

TEST(FramePipeline, FinishWithoutAheadIsRefused) {
  const AttendOptions options =
      testing::WithFeatures("[{name: colour_contrast}, {name: intensity_contrast}]");
  ExecutionContext execution(2);
  FramePipeline pipeline(options, BuiltinFeatures(), testing::SetupFor(false), &execution);
  FrameRecord record;
  EXPECT_THROW(pipeline.Finish(&record), InternalError);
}

}  // namespace
}  // namespace attend
