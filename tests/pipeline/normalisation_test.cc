// Per-feature normalisations: a feature entry's `normalisation` picks a built-in one or one a
// plugin registered (FeatureRegistry::AddNormalisation); unknown names, names clashing with the
// built-in ones and broken results are configuration errors.
#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "features/builtin.h"
#include "pipeline/frame_pipeline.h"
#include "pipeline/options_io.h"
#include "saliency/saliency.h"
#include "tests/support/error_message.h"
#include "tests/support/pipeline_options.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

using testing::WithFeatures;

FeatureSetup MonocularSetup() { return testing::SetupFor(false); }

// A grey frame with a bright square and three coloured ones: several local maxima of contrast,
// so local_maxima and minmax differ.
StereoFrame Frame() {
  StereoFrame frame;
  frame.left = cv::Mat(60, 80, CV_8UC3, cv::Scalar(90, 90, 90));
  cv::rectangle(frame.left, cv::Rect(4, 4, 16, 14), cv::Scalar(230, 230, 230), cv::FILLED);
  cv::rectangle(frame.left, cv::Rect(40, 6, 14, 12), cv::Scalar(40, 40, 220), cv::FILLED);
  cv::rectangle(frame.left, cv::Rect(10, 36, 12, 14), cv::Scalar(40, 200, 60), cv::FILLED);
  cv::rectangle(frame.left, cv::Rect(52, 34, 16, 16), cv::Scalar(200, 120, 40), cv::FILLED);
  return frame;
}

FeatureRegistry WithConstantNormalisation(float value) {
  FeatureRegistry registry = BuiltinFeatures();
  registry.SetOrigin("libnorm.so");
  registry.AddNormalisation("constant", "every pixel the same",
                            [value](const cv::Mat& map, cv::Mat* out) {
                              *out = cv::Mat(map.size(), CV_32FC1, cv::Scalar(value));
                            });
  return registry;
}

// The tests' execution context (util/execution_context.h): one thread.
ExecutionContext* Execution() {
  static ExecutionContext execution(1);
  return &execution;
}

TEST(Normalisation, AFeatureUsesTheNormalisationItsEntryNames) {
  const AttendOptions options = WithFeatures(
      "[{name: intensity_contrast, normalisation: constant}, "
      "{name: colour_contrast, normalisation: local_maxima}, {name: skin}]");
  FramePipeline pipeline(options, WithConstantNormalisation(0.25f), MonocularSetup(), Execution());
  FrameRecord record;
  pipeline.Process(Frame(), &record);
  const cv::Mat& plugin = pipeline.normalised()[0];
  EXPECT_EQ(cv::countNonZero(plugin != 0.25f), 0);
  // A built-in one by name, and the default (saliency.normalisation, minmax) for the third.
  SaliencyOptions local = options.saliency;
  local.normalisation = "local_maxima";
  cv::Mat expected;
  NormaliseMap(pipeline.features()[1].map, local, &expected);
  EXPECT_EQ(cv::norm(pipeline.normalised()[1], expected, cv::NORM_INF), 0.0);
  cv::Mat minmax;  // the default would give another map here
  NormaliseMap(pipeline.features()[1].map, options.saliency, &minmax);
  EXPECT_GT(cv::norm(minmax, expected, cv::NORM_INF), 0.0);
  NormaliseMap(pipeline.features()[2].map, options.saliency, &expected);
  EXPECT_EQ(cv::norm(pipeline.normalised()[2], expected, cv::NORM_INF), 0.0);
}

// saliency.normalisation names a plugin's normalisation as well as a built-in one: it is then
// every feature's that names none. Without plugins, an unknown name is refused at its line.
TEST(Normalisation, SaliencyNormalisationMayNameAPluginsNormalisation) {
  AttendOptions options = WithFeatures("[{name: intensity_contrast}, {name: colour_contrast}]");
  options.saliency.normalisation = "constant";
  FramePipeline pipeline(options, WithConstantNormalisation(0.5f), MonocularSetup(), Execution());
  FrameRecord record;
  pipeline.Process(Frame(), &record);
  for (const cv::Mat& map : pipeline.normalised()) EXPECT_EQ(cv::countNonZero(map != 0.5f), 0);
  EXPECT_NEAR(pipeline.saliency().at<float>(0, 0), 0.5f, 1e-6);

  std::string message = testing::ConfigErrorOf(
      [&] { FramePipeline unknown(options, BuiltinFeatures(), MonocularSetup(), Execution()); });
  EXPECT_NE(message.find("saliency.normalisation: unknown normalisation 'constant'"),
            std::string::npos)
      << message;
  message = testing::ConfigErrorOf(
      [] { ReadOptions(ParamBlock::Parse("saliency:\n  normalisation: minmx\n", "n.yaml")); });
  EXPECT_NE(message.find("n.yaml:2: saliency.normalisation: 'minmx' is not one of minmax, "
                         "local_maxima (did you mean 'minmax'?)"),
            std::string::npos)
      << message;
}

TEST(Normalisation, UnknownOrClashingNamesAndBrokenResultsAreConfigurationErrors) {
  std::string message = testing::ConfigErrorOf([] {
    FramePipeline pipeline(WithFeatures("[{name: intensity_contrast, normalisation: constnt}]"),
                           WithConstantNormalisation(0.5f), MonocularSetup(), Execution());
  });
  EXPECT_NE(message.find("test.yaml:1"), std::string::npos) << message;
  EXPECT_NE(message.find("did you mean 'constant'"), std::string::npos) << message;

  // A library that registers a built-in name is refused when it registers it.
  FeatureRegistry clash = BuiltinFeatures();
  clash.SetOrigin("libclash.so");
  message = testing::ConfigErrorOf([&] {
    clash.AddNormalisation("minmax", "", [](const cv::Mat& map, cv::Mat* out) { *out = map; });
  });
  EXPECT_NE(message.find("libclash.so"), std::string::npos) << message;
  EXPECT_NE(message.find("built in"), std::string::npos) << message;

  FramePipeline broken(WithFeatures("[{name: intensity_contrast, normalisation: constant}]"),
                       WithConstantNormalisation(2.f), MonocularSetup(), Execution());
  FrameRecord record;
  message = testing::ConfigErrorOf([&] { broken.Process(Frame(), &record); });
  EXPECT_NE(message.find("intensity_contrast"), std::string::npos) << message;
  EXPECT_NE(message.find("libnorm.so"), std::string::npos) << message;
}

}  // namespace
}  // namespace attend
