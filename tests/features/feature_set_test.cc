#include "features/feature_set.h"

#include <gtest/gtest.h>

#include <atomic>
#include <fstream>

#include "colour/colour.h"
#include "features/builtin.h"
#include "features/lazy_frame_context.h"
#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

using testing::ConfigErrorOf;

// A feature list parsed from YAML, as the configuration gives it.
std::vector<FeatureSpec> Specs(const std::string& yaml) {
  return ReadFeatureList(ParamBlock::Parse("features: " + yaml, "test.yaml"), "features");
}

cv::Mat Picture() {
  cv::Mat image(48, 64, CV_8UC3, cv::Scalar(120, 120, 120));
  image(cv::Rect(8, 8, 20, 16)).setTo(cv::Scalar(30, 30, 220));
  image(cv::Rect(36, 20, 20, 20)).setTo(cv::Scalar(140, 172, 224));  // skin-like
  image(cv::Rect(10, 30, 12, 12)).setTo(cv::Scalar(250, 250, 250));
  return image;
}

// Test plugins: a constant map, a map of the wrong size, one that throws.
class Constant : public FeatureMap {
 public:
  explicit Constant(float value) : value_(value) {}
  void Compute(const FrameContext& context, cv::Mat* out) override {
    out->create(context.size(), CV_32FC1);
    out->setTo(value_);
  }

 private:
  float value_;
};
class WrongSize : public FeatureMap {
 public:
  void Compute(const FrameContext&, cv::Mat* out) override { out->create(3, 3, CV_32FC1); }
};
class Throws : public FeatureMap {
 public:
  void Compute(const FrameContext&, cv::Mat*) override { throw ConfigError("thrown by plugin"); }
};

FeatureRegistry RegistryWithTestPlugins() {
  FeatureRegistry registry = BuiltinFeatures();
  registry.SetOrigin("libtest.so");
  registry.Add("constant", "a constant", [](const ParamBlock& params, const FeatureSetup&) {
    return std::make_unique<Constant>(static_cast<float>(params.GetDouble("value", 1.0)));
  });
  registry.Add("wrong_size", "", [](const ParamBlock&, const FeatureSetup&) {
    return std::make_unique<WrongSize>();
  });
  registry.Add("throws", "",
               [](const ParamBlock&, const FeatureSetup&) { return std::make_unique<Throws>(); });
  return registry;
}

TEST(FeatureSet, UnknownNameSuggestsTheClosest) {
  const std::string message = ConfigErrorOf(
      [] { FeatureSet set(Specs("[{name: colour_contrst}]"), BuiltinFeatures(), {}); });
  EXPECT_NE(message.find("test.yaml:1"), std::string::npos) << message;
  EXPECT_NE(message.find("did you mean 'colour_contrast'"), std::string::npos) << message;
  EXPECT_NE(message.find("intensity_contrast"), std::string::npos) << message;
}

TEST(FeatureSet, UnknownPluginParameterIsAnError) {
  const std::string message = ConfigErrorOf([] {
    FeatureSetup setup;
    setup.home = testing::ProjectRoot();
    FeatureSet set(Specs("[{name: skin, outptu: soft}]"), BuiltinFeatures(), setup);
  });
  EXPECT_NE(message.find("outptu"), std::string::npos) << message;
  EXPECT_NE(message.find("test.yaml:1"), std::string::npos) << message;
  EXPECT_NE(message.find("did you mean 'output'"), std::string::npos) << message;
}

TEST(FeatureSet, BadPluginParameterValueNamesTheKey) {
  const std::string message = ConfigErrorOf(
      [] { FeatureSet set(Specs("[{name: skin, output: fuzzy}]"), BuiltinFeatures(), {}); });
  EXPECT_NE(message.find("features.0.output"), std::string::npos) << message;
}

TEST(FeatureSet, MissingModelFileNamesTheKeyAndPlaces) {
  const std::string message = ConfigErrorOf([] {
    FeatureSetup setup;
    setup.home = "/nonexistent-home";
    FeatureSet set(Specs("[{name: skin, model: no/such/model.yaml}]"), BuiltinFeatures(), setup);
  });
  EXPECT_NE(message.find("features.0.model"), std::string::npos) << message;
  EXPECT_NE(message.find("/nonexistent-home"), std::string::npos) << message;
}

TEST(FeatureSet, DisabledFeatureIsCheckedButNotRun) {
  const FeatureRegistry registry = RegistryWithTestPlugins();
  FeatureSet set(Specs("[{name: constant, value: 2}, {name: throws, enabled: false}]"), registry,
                 {});
  ASSERT_EQ(set.results().size(), 1u);
  LazyFrameContext context;
  const cv::Mat image = Picture();
  context.Reset(0, image);
  set.Compute(context);
  EXPECT_EQ(set.results()[0].name, "constant");
  EXPECT_EQ(set.results()[0].map.at<float>(3, 3), 2.f);
  // Its parameters are still checked.
  EXPECT_NE(ConfigErrorOf([&] {
              FeatureSet bad(Specs("[{name: constant, enabled: false, valeu: 3}]"), registry, {});
            }).find("valeu"),
            std::string::npos);
}

// A plugin that writes what it is told into a log.
class Logging : public FeatureMap {
 public:
  explicit Logging(std::vector<std::string>* log) : log_(log) {}
  void BeginSequence(const SequenceStart& start) override {
    log_->push_back("begin " + start.name + " " + std::to_string(start.size.width) + "x" +
                    std::to_string(start.size.height) + " " + std::to_string(start.first_frame));
  }
  void EndSequence() override { log_->push_back("end"); }
  void Compute(const FrameContext& context, cv::Mat* out) override {
    log_->push_back("frame " + std::to_string(context.frame_index()));
    *out = cv::Mat::zeros(context.size(), CV_32FC1);
  }

 private:
  std::vector<std::string>* log_;
};

TEST(FeatureSet, EnabledFeaturesHearWhereASequenceStartsAndEnds) {
  std::vector<std::string> log;
  FeatureRegistry registry;
  std::vector<std::string> disabled_log;
  registry.Add("logging", "", [&log](const ParamBlock&, const FeatureSetup&) {
    return std::make_unique<Logging>(&log);
  });
  registry.Add("disabled", "", [&disabled_log](const ParamBlock&, const FeatureSetup&) {
    return std::make_unique<Logging>(&disabled_log);
  });
  FeatureSet set(Specs("[{name: logging}, {name: disabled, enabled: false}]"), registry, {});
  LazyFrameContext context;
  const cv::Mat image = Picture();
  set.BeginSequence({"walk", image.size(), false, 4});
  for (int frame = 4; frame < 6; ++frame) {
    context.Reset(frame, image);
    set.Compute(context);
  }
  set.EndSequence();
  const std::string size = std::to_string(image.cols) + "x" + std::to_string(image.rows);
  EXPECT_EQ(log,
            (std::vector<std::string>{"begin walk " + size + " 4", "frame 4", "frame 5", "end"}));
  EXPECT_TRUE(disabled_log.empty());
}

TEST(FeatureSet, ConcurrentAndSerialGiveTheSameMaps) {
  const std::vector<FeatureSpec> specs = Specs(
      "[{name: colour_contrast}, {name: intensity_contrast}, {name: skin, output: soft}, "
      "{name: constant, value: 4}]");
  const FeatureRegistry registry = RegistryWithTestPlugins();
  FeatureSetup setup;
  setup.home = testing::ProjectRoot();
  FeatureSet serial(specs, registry, setup);
  FeatureSet concurrent(specs, registry, setup);
  ThreadPool pool(2);
  const cv::Mat image = Picture();
  for (int round = 0; round < 3; ++round) {
    LazyFrameContext a, b;
    a.Reset(round, image);
    b.Reset(round, image);
    serial.Compute(a);
    concurrent.Compute(b, &pool);
    for (size_t i = 0; i < serial.results().size(); ++i) {
      EXPECT_EQ(cv::norm(serial.results()[i].map, concurrent.results()[i].map, cv::NORM_INF), 0.0)
          << serial.results()[i].name;
    }
  }
  EXPECT_GT(cv::countNonZero(serial.results()[0].map), 0);
}

TEST(FeatureSet, WrongOutputNamesThePluginAndItsLibrary) {
  FeatureSet set(Specs("[{name: wrong_size}]"), RegistryWithTestPlugins(), {});
  LazyFrameContext context;
  const cv::Mat image = Picture();
  context.Reset(0, image);
  // The plugin's failure (exit status 4), not the configuration's.
  ThreadPool pool(1);
  const std::string message = testing::ErrorOf<PluginError>([&] { set.Compute(context, &pool); });
  EXPECT_NE(message.find("feature 'wrong_size' (libtest.so)"), std::string::npos) << message;
  EXPECT_NE(message.find("64x48"), std::string::npos) << message;
}

TEST(FeatureSet, FirstFailingPluginInListOrderIsReported) {
  FeatureSet set(Specs("[{name: constant}, {name: throws}, {name: wrong_size}]"),
                 RegistryWithTestPlugins(), {});
  LazyFrameContext context;
  const cv::Mat image = Picture();
  context.Reset(0, image);
  ThreadPool pool(2);
  for (ThreadPool* threads : {static_cast<ThreadPool*>(nullptr), &pool}) {
    EXPECT_EQ(ConfigErrorOf([&] { set.Compute(context, threads); }), "thrown by plugin");
  }
}

TEST(FeatureRegistry, NameTakenTwiceIsAnError) {
  FeatureRegistry registry = BuiltinFeatures();
  registry.SetOrigin("libmine.so");
  const std::string message = ConfigErrorOf([&] {
    registry.Add("skin", "", [](const ParamBlock&, const FeatureSetup&) {
      return std::make_unique<Constant>(0.f);
    });
  });
  EXPECT_NE(message.find("libmine.so"), std::string::npos) << message;
  EXPECT_NE(message.find("built-in"), std::string::npos) << message;
}

TEST(FeatureSetup, RelativePathsFallBackToHome) {
  testing::TempDir home;
  home.Write("model.yaml", "x: 1\n");
  FeatureSetup setup;
  setup.home = home.path().string();
  const ParamBlock params = ParamBlock::Parse("model: model.yaml", "test.yaml");
  EXPECT_EQ(setup.ResolvePath(params, "model", "model.yaml"), home.File("model.yaml"));
  EXPECT_EQ(setup.ResolvePath(params, "model", home.File("model.yaml")), home.File("model.yaml"));
}

TEST(FrameContext, SharesOneConversionAndSegmentationPerFrame) {
  LazyFrameContext context;
  const cv::Mat image = Picture();
  context.Reset(0, image);
  const Segmentation* first = &context.Regions();
  EXPECT_EQ(first, &context.Regions());
  cv::Mat cylinder;
  BgrToCylinder(image, &cylinder);
  EXPECT_EQ(cv::norm(cylinder, context.Cylinder(), cv::NORM_INF), 0.0);
  const int regions = static_cast<int>(context.Regions().regions.size());
  EXPECT_GE(regions, 4);
  // A new frame recomputes.
  const cv::Mat flat(48, 64, CV_8UC3, cv::Scalar(10, 200, 10));
  context.Reset(1, flat);
  EXPECT_EQ(context.Regions().regions.size(), 1u);
  EXPECT_EQ(context.frame_index(), 1);
  EXPECT_FALSE(context.stereo());
}

}  // namespace
}  // namespace attend
