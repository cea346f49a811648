// The generated option tables (pipeline/options_doc.h): configs/README.md holds what the field
// tables give, every key has its row, and the markers are checked.
#include "pipeline/options_doc.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "config/param_block.h"
#include "features/builtin.h"
#include "features/detectors.h"
#include "pipeline/options_io.h"
#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

std::string FileText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(OptionsDoc, ConfigsReadmeHoldsTheGeneratedTables) {
  const std::string path = testing::ProjectRoot() + "/configs/README.md";
  const std::string readme = FileText(path);
  ASSERT_FALSE(readme.empty());
  EXPECT_TRUE(WithGeneratedTables(readme) == readme)
      << "configs/README.md's option tables differ from the options structs' field tables; "
         "regenerate them with `build/attend options-doc --write configs/README.md` (from the "
         "source folder) and commit the file";
}

TEST(OptionsDoc, EveryKeyHasItsRowWithItsRangeAndDefault) {
  const std::string readme = FileText(testing::ProjectRoot() + "/configs/README.md");
  for (const FieldDescription& line : DescribeEveryKey()) {
    if (line.type == "list of features") continue;  // the features' table lists them
    EXPECT_NE(readme.find("| `" + line.key + "` | "), std::string::npos)
        << line.key << " has no row in configs/README.md";
  }
  for (const BuiltinFeature& feature : BuiltinFeatureTable()) {
    EXPECT_NE(readme.find(std::string("| `features.") + feature.name + "` | feature |"),
              std::string::npos)
        << feature.name;
  }
  // The examples of drift: the ranges are the code's.
  EXPECT_NE(readme.find("| `tracker.alpha` | number | `0.1` | [0.001, 1] | kinds: bip. "),
            std::string::npos);
  EXPECT_NE(readme.find("| `tracker.t_colour` | number | `30` | [0.001, 1000] |"),
            std::string::npos);
  EXPECT_NE(readme.find("| `select.max_new` | int | `2` | [1, 1000] | targets started in one "
                        "frame |"),
            std::string::npos);
}

TEST(OptionsDoc, TablesReplaceWhatIsBetweenTheMarkersOnly) {
  const std::string text =
      "prose\n<!-- options: drop -->\n| stale |\n<!-- end options -->\nmore prose\n";
  const std::string generated = WithGeneratedTables(text);
  EXPECT_EQ(generated.rfind("prose\n<!-- options: drop -->\n| key | type |", 0), 0u) << generated;
  EXPECT_EQ(generated.find("stale"), std::string::npos);
  EXPECT_NE(generated.find("| `drop.frames` | int | `15` |"), std::string::npos) << generated;
  EXPECT_NE(generated.find("<!-- end options -->\nmore prose\n"), std::string::npos);
  EXPECT_EQ(WithGeneratedTables(generated), generated);
  // The choices of an enum, and a list's, in the range column.
  EXPECT_NE(OptionTable("tracker").find("| `tracker.kind` | choice | `bip` | `bip`, `kcf`, "
                                        "`csrt` |"),
            std::string::npos)
      << OptionTable("tracker");
}

TEST(OptionsDoc, BadMarkersNameTheirLine) {
  EXPECT_NE(testing::ConfigErrorOf([] { WithGeneratedTables("a\n<!-- options: nosuch -->\n"); })
                .find("line 2: no configuration section 'nosuch'"),
            std::string::npos);
  EXPECT_NE(testing::ConfigErrorOf([] {
              WithGeneratedTables("<!-- options: drop -->\n| row |\n");
            }).find("line 1: no <!-- end options --> after it"),
            std::string::npos);
}

TEST(OptionsDoc, WriteRegeneratesAFileInPlaceOnce) {
  testing::TempDir dir;
  const std::string path = dir.File("README.md");
  std::ofstream(path) << "# x\n<!-- options: inhibition -->\n<!-- end options -->\n";
  EXPECT_TRUE(WriteGeneratedTables(path));
  EXPECT_NE(FileText(path).find("`inhibition.margin`"), std::string::npos);
  EXPECT_FALSE(WriteGeneratedTables(path));
}

// Each built-in feature's table lists exactly the keys its factory reads.
// The keys a feature made from `params` asked for, sorted, without the ones every feature has.
std::vector<std::string> KeysRead(const FeatureRegistry& registry, const FeatureSetup& setup,
                                  const std::string& name, const std::string& params) {
  FeatureSpec spec;
  spec.name = name;
  spec.params = ParamBlock::Parse(params, "test");
  registry.Create(spec, setup);
  std::vector<std::string> read;
  for (const std::string& key : spec.params.KnownKeys()) {
    if (key != "name" && key != "weight" && key != "enabled" && key != "normalisation") {
      read.push_back(key);
    }
  }
  std::sort(read.begin(), read.end());
  return read;
}

// The described keys, sorted: those of the dnn backend ("dnn: KEY", read only with `backend:
// dnn`) when `dnn`, the others otherwise (`backend` in both).
std::vector<std::string> KeysDescribed(const BuiltinFeature& feature, bool dnn) {
  std::vector<std::string> described;
  for (const FieldDescription& line : feature.keys()) {
    const bool dnn_key = line.key.rfind("dnn: ", 0) == 0;
    if (dnn_key && dnn) described.push_back(line.key.substr(5));
    if (!dnn_key && (!dnn || line.key == "backend")) described.push_back(line.key);
  }
  std::sort(described.begin(), described.end());
  return described;
}

TEST(OptionsDoc, EachFeaturesKeysAreTheKeysItReads) {
  FeatureSetup setup;
  setup.home = testing::ProjectRoot();
  const FeatureRegistry registry = BuiltinFeatures();
  for (const BuiltinFeature& feature : BuiltinFeatureTable()) {
    // `objects` has no model by default; the dnn backends are checked below.
    if (std::string(feature.name) == "objects") continue;
    EXPECT_EQ(KeysRead(registry, setup, feature.name, "{}"), KeysDescribed(feature, false))
        << feature.name;
  }
}

// The dnn backend's keys, with the reference data's networks (skipped without them).
TEST(OptionsDoc, EachDnnBackendsKeysAreTheKeysItReads) {
  const std::string models = testing::SharedData() + "/models";
  if (!std::filesystem::exists(models + "/yolox/yolox_nano.onnx") ||
      !std::filesystem::exists(models + "/yunet/yunet_n_640_640.onnx")) {
    GTEST_SKIP() << "no " << models << " (the reference data's models)";
  }
  FeatureSetup setup;
  setup.home = testing::ProjectRoot();
  const FeatureRegistry registry = BuiltinFeatures();
  const std::string yolox = "{backend: dnn, model: " + models + "/yolox/yolox_nano.onnx}";
  const std::string yunet = "{backend: dnn, model: " + models + "/yunet/yunet_n_640_640.onnx}";
  for (const BuiltinFeature& feature : BuiltinFeatureTable()) {
    const std::string name = feature.name;
    if (name != "people" && name != "faces" && name != "objects") continue;
    std::vector<std::string> described = KeysDescribed(feature, true);
    if (name == "objects") {
      // Every key of `objects` is the dnn backend's (it has no other), described plainly.
      described = KeysDescribed(feature, false);
    } else {
      // The channel's own keys are read whatever the backend.
      for (const FieldDescription& line : DescribeFields(ObjectChannelOptions::Fields())) {
        described.push_back(line.key);
      }
      std::sort(described.begin(), described.end());
    }
    EXPECT_EQ(KeysRead(registry, setup, name, name == "faces" ? yunet : yolox),
              described)
        << feature.name;
  }
}

}  // namespace
}  // namespace attend
