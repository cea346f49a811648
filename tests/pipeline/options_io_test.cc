#include "pipeline/options_io.h"

#include <gtest/gtest.h>

#include <fstream>
#include <functional>
#include <sstream>

#include "features/builtin.h"
#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"
#include "util/strings.h"

namespace attend {
namespace {

using testing::ConfigErrorOf;
using testing::ErrorOf;
using testing::InputErrorOf;

std::string DefaultConfig() { return testing::ProjectRoot() + "/configs/default.yaml"; }

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(OptionsIo, StructDefaultsAreValid) {
  const AttendOptions options;
  EXPECT_EQ(options.sequence.Check(), "");
  EXPECT_EQ(options.output.Check(), "");
}

TEST(OptionsIo, DefaultYamlSetsEveryKeyToTheStructDefault) {
  const ParamBlock root = ParamBlock::LoadFile(DefaultConfig());
  for (const std::string& key : ConfigurationKeys()) {
    const std::vector<std::string> parts = Split(key, '.');
    ParamBlock block = root;
    for (size_t i = 0; i + 1 < parts.size(); ++i) block = block.Child(parts[i]);
    EXPECT_TRUE(block.Has(parts.back())) << key << " is not set in configs/default.yaml";
  }
  const AttendOptions options = LoadOptions(DefaultConfig(), {});
  const AttendOptions defaults;
  // The file and the struct agree: a reader of either sees the same defaults.
  EXPECT_EQ(OptionsToYaml(options).substr(0, OptionsToYaml(options).find("features:")),
            OptionsToYaml(defaults).substr(0, OptionsToYaml(defaults).find("features:")));
  ASSERT_EQ(options.features.size(), 4u);
  EXPECT_EQ(options.features[0].name, "colour_contrast");
  EXPECT_EQ(options.features[2].name, "skin");
  EXPECT_EQ(options.features[3].name, "disparity");
}

TEST(OptionsIo, EveryKeyIsDocumentedInConfigsReadme) {
  const std::string readme = ReadText(testing::ProjectRoot() + "/configs/README.md");
  ASSERT_FALSE(readme.empty());
  for (const std::string& key : ConfigurationKeys()) {
    EXPECT_NE(readme.find("`" + key + "`"), std::string::npos)
        << key << " is not documented in configs/README.md";
  }
}

// Each built-in feature's parameters, as the plugin asks for them, are documented as
// `features.<name>.<key>` and set in the default configuration when it lists the feature.
TEST(OptionsIo, EveryBuiltinFeatureParameterIsDocumentedAndSet) {
  const std::string readme = ReadText(testing::ProjectRoot() + "/configs/README.md");
  const AttendOptions defaults = LoadOptions(DefaultConfig(), {});
  const FeatureRegistry registry = BuiltinFeatures();
  FeatureSetup setup;
  setup.home = testing::ProjectRoot();
  for (const std::string& name : registry.Names()) {
    EXPECT_NE(readme.find("`features." + name + "`"), std::string::npos) << name;
    // `objects` is a network's and has no default model: its keys are checked with the
    // reference data's network (OptionsDoc.EachDnnBackendsKeysAreTheKeysItReads).
    if (name == "objects") continue;
    FeatureSpec spec;
    spec.name = name;
    registry.Create(spec, setup);
    const FeatureSpec* listed = nullptr;
    for (const FeatureSpec& entry : defaults.features) {
      if (entry.name == name) listed = &entry;
    }
    for (const std::string& key : spec.params.KnownKeys()) {
      if (key == "name" || key == "weight" || key == "enabled") continue;
      EXPECT_NE(readme.find("`features." + name + "." + key + "`"), std::string::npos)
          << name << "." << key << " is not documented in configs/README.md";
      if (listed != nullptr) {
        EXPECT_TRUE(listed->params.Has(key)) << name << "." << key << " is not in default.yaml";
      }
    }
  }
}

TEST(OptionsIo, EffectiveConfigurationRoundTrips) {
  const AttendOptions options =
      LoadOptions(DefaultConfig(), {"sequence.stride=3", "output.dump=[]", "sequence.resize=native",
                                    "features.skin.weight=0.25", "features.skin.output=soft"});
  EXPECT_EQ(options.sequence.stride, 3);
  EXPECT_TRUE(options.output.dump.empty());
  const std::string yaml = OptionsToYaml(options);
  const AttendOptions again = ReadOptions(ParamBlock::Parse(yaml, "config.yaml"));
  EXPECT_EQ(OptionsToYaml(again), yaml);
  EXPECT_EQ(again.sequence.resize, "native");
  EXPECT_DOUBLE_EQ(again.features[2].weight, 0.25);
  EXPECT_EQ(again.features[2].params.GetString("output", ""), "soft");  // plugin keys survive
}

// tracker.kind chooses the tracker; an unknown kind names the key and line.
TEST(OptionsIo, TrackerKindIsReadAndAnUnknownKindNamesTheLine) {
  EXPECT_EQ(LoadOptions(DefaultConfig(), {}).attention.tracker.kind, TrackerKind::kBip);
  EXPECT_EQ(LoadOptions(DefaultConfig(), {"tracker.kind=csrt"}).attention.tracker.kind,
            TrackerKind::kCsrt);
  testing::TempDir dir;
  const std::string path = dir.Write("k.yaml", "tracker:\n  alpha: 0.1\n  kind: mosse\n");
  const std::string message = ConfigErrorOf([&] { LoadOptions(path, {}); });
  EXPECT_NE(message.find(path + ":3: tracker.kind: 'mosse' is not one of bip, kcf, csrt"),
            std::string::npos)
      << message;
}

// A key of another kind than the chosen one is an error when set away from its default
// (naming its line), and allowed at its default: the shipped defaults, which set every key,
// can change the kind alone, and RUN/config.yaml of such a run reads back.
TEST(OptionsIo, AnOptionOfAnotherTrackerKindIsAnErrorUnlessAtItsDefault) {
  for (const char* kind : {"kcf", "csrt"}) {
    const AttendOptions options =
        LoadOptions(DefaultConfig(), {std::string("tracker.kind=") + kind, "tracker.lost_frames=3"});
    EXPECT_EQ(options.attention.tracker.opencv.lost_frames, 3);
    const std::string yaml = OptionsToYaml(options);
    EXPECT_EQ(OptionsToYaml(ReadOptions(ParamBlock::Parse(yaml, "config.yaml"))), yaml);
  }
  testing::TempDir dir;
  std::string path = dir.Write("f.yaml", "tracker:\n  kind: kcf\n  t_colour: 30\n  alpha: 0.2\n");
  std::string message = ConfigErrorOf([&] { LoadOptions(path, {}); });
  EXPECT_NE(message.find(path + ":4: tracker.alpha: is used only by tracker.kind bip, but "
                                "tracker.kind is kcf (" + path + ":2)"),
            std::string::npos)
      << message;
  path = dir.Write("g.yaml", "tracker:\n  lost_frames: 5\n");
  message = ConfigErrorOf([&] { LoadOptions(path, {}); });
  EXPECT_NE(message.find(path + ":2: tracker.lost_frames: is used only by tracker.kind kcf or "
                                "csrt, but tracker.kind is bip"),
            std::string::npos)
      << message;
  message = ConfigErrorOf(
      [&] { LoadOptions(DefaultConfig(), {"tracker.kind=csrt", "tracker.mode=thesis"}); });
  EXPECT_NE(message.find("--set tracker.mode=thesis: tracker.mode: is used only by tracker.kind "
                         "bip"),
            std::string::npos)
      << message;
  message = ConfigErrorOf(
      [&] { LoadOptions(DefaultConfig(), {"tracker.kind=csrt", "tracker.kcf_detect_thresh=0"}); });
  EXPECT_NE(message.find("tracker.kcf_detect_thresh: is used only by tracker.kind kcf, but "
                         "tracker.kind is csrt"),
            std::string::npos)
      << message;
  EXPECT_FLOAT_EQ(LoadOptions(DefaultConfig(), {"tracker.kind=kcf", "tracker.kcf_detect_thresh=0"})
                      .attention.tracker.opencv.kcf_detect_thresh,
                  0.f);
  // The chosen kind's own options are still checked.
  message = ConfigErrorOf([&] { LoadOptions(DefaultConfig(), {"tracker.kind=kcf",
                                                              "tracker.lost_frames=0"}); });
  EXPECT_NE(message.find("tracker.lost_frames"), std::string::npos) << message;
}

TEST(OptionsIo, ErrorsNameKeyLineAndClosestKey) {
  testing::TempDir dir;
  std::string path = dir.Write("a.yaml", "sequence:\n  stride: 2\n  widht: 100\n");
  std::string message = ConfigErrorOf([&] { LoadOptions(path, {}); });
  EXPECT_NE(message.find(path + ":3: unknown key 'widht' in sequence (did you mean 'width'?)"),
            std::string::npos)
      << message;

  path = dir.Write("b.yaml", "sequence: {}\noutptu: {}\n");
  message = ConfigErrorOf([&] { LoadOptions(path, {}); });
  EXPECT_NE(message.find(path + ":2: unknown key 'outptu' (did you mean 'output'?)"),
            std::string::npos)
      << message;

  path = dir.Write("c.yaml", "sequence:\n  stride: 0\n");
  message = ConfigErrorOf([&] { LoadOptions(path, {}); });
  EXPECT_NE(
      message.find(path + ":2: sequence.stride: value 0 out of range: must be in [1, 1000000]"),
      std::string::npos)
      << message;

  path = dir.Write("d.yaml", "output:\n  dump: [overlay, salience]\n");
  message = ConfigErrorOf([&] { LoadOptions(path, {}); });
  EXPECT_NE(message.find(path + ":2: output.dump: 'salience' is not one of"), std::string::npos)
      << message;

  path = dir.Write("e.yaml", "sequence:\n  first_frame: 10\n  last_frame: 5\n");
  message = ConfigErrorOf([&] { LoadOptions(path, {}); });
  EXPECT_NE(message.find(path + ":2: sequence: "), std::string::npos) << message;
  EXPECT_NE(message.find("last_frame"), std::string::npos) << message;

  message = ConfigErrorOf([&] { LoadOptions(dir.File("missing.yaml"), {}); });
  EXPECT_NE(message.find("missing.yaml: the YAML file does not exist"), std::string::npos) << message;

  message = ConfigErrorOf([&] { LoadOptions(DefaultConfig(), {"sequence.strid=2"}); });
  EXPECT_NE(message.find("--set sequence.strid=2: unknown key 'strid' in sequence (did you mean "
                         "'stride'?)"),
            std::string::npos)
      << message;

  message = ConfigErrorOf([&] {
    LoadOptions(DefaultConfig(), {"output.video=true", "output.dump=[]"});
  });
  EXPECT_NE(message.find("video needs 'overlay' in dump"), std::string::npos) << message;
}

}  // namespace
}  // namespace attend
