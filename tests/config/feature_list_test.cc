#include "config/feature_list.h"

#include <gtest/gtest.h>

#include <functional>

#include "tests/support/error_message.h"
#include "util/error.h"

namespace attend {
namespace {

using testing::ConfigErrorOf;
using testing::ErrorOf;
using testing::InputErrorOf;

constexpr const char* kList =
    "features:\n"
    "  - {name: colour_contrast, weight: 1.0}\n"
    "  - {name: skin, weight: 0.5, model: configs/skin_tsl.yaml}\n"
    "  - name: disparity\n"
    "    max_disparity: 32\n"
    "    windw: 9\n";

TEST(FeatureList, ParsesNamesWeightsAndDefaultsWeightToOne) {
  const ParamBlock root = ParamBlock::Parse(kList, "c.yaml");
  const std::vector<FeatureSpec> specs = ReadFeatureList(root, "features");
  ASSERT_EQ(specs.size(), 3u);
  EXPECT_EQ(specs[0].name, "colour_contrast");
  EXPECT_DOUBLE_EQ(specs[1].weight, 0.5);
  EXPECT_DOUBLE_EQ(specs[2].weight, 1.0);
  EXPECT_EQ(specs[1].params.GetString("model", ""), "configs/skin_tsl.yaml");
}

TEST(FeatureList, PluginBlockReportsUnknownPluginKeysWithLine) {
  const ParamBlock root = ParamBlock::Parse(kList, "c.yaml");
  const std::vector<FeatureSpec> specs = ReadFeatureList(root, "features");
  // What a disparity plugin would do with its block: read its keys, then check.
  const FeatureSpec& disparity = specs[2];
  EXPECT_EQ(disparity.params.GetInt("max_disparity", 64, Range::Above(0)), 32);
  disparity.params.GetInt("window", 9, Range::Above(0));
  const std::string message = ConfigErrorOf([&] { disparity.params.CheckNoUnknownKeys(); });
  EXPECT_NE(message.find("c.yaml:6: unknown key 'windw' in features.2"), std::string::npos)
      << message;
  EXPECT_NE(message.find("did you mean 'window'"), std::string::npos) << message;
  // name and weight are known to every block.
  specs[0].params.CheckNoUnknownKeys();
}

TEST(FeatureList, RejectsMissingNameNegativeWeightDuplicatesAndNonMaps) {
  std::string message = ConfigErrorOf([] {
    ReadFeatureList(ParamBlock::Parse("features:\n  - {weight: 1}\n", "c.yaml"), "features");
  });
  EXPECT_NE(message.find("c.yaml:2: features.0.name: required key is missing"), std::string::npos)
      << message;
  message = ConfigErrorOf([] {
    ReadFeatureList(ParamBlock::Parse("features:\n  - {name: a, weight: -1}\n", "c.yaml"),
                    "features");
  });
  EXPECT_NE(message.find("features.0.weight: value -1 out of range: must be >= 0"),
            std::string::npos)
      << message;
  message = ConfigErrorOf([] {
    ReadFeatureList(ParamBlock::Parse("features:\n  - {name: a}\n  - {name: a}\n", "c.yaml"),
                    "features");
  });
  EXPECT_NE(message.find("c.yaml:3: features.1.name: feature 'a' is listed twice"),
            std::string::npos)
      << message;
  message = ConfigErrorOf(
      [] { ReadFeatureList(ParamBlock::Parse("features:\n  - skin\n", "c.yaml"), "features"); });
  EXPECT_NE(message.find("expected a map of keys"), std::string::npos) << message;
}

TEST(FeatureList, OverrideByNameReachesThePluginBlock) {
  ParamBlock root = ParamBlock::Parse(kList, "c.yaml");
  root.Override("features.disparity.max_disparity=48");
  const std::vector<FeatureSpec> specs = ReadFeatureList(root, "features");
  EXPECT_EQ(specs[2].params.GetInt("max_disparity", 64), 48);
  EXPECT_NE(specs[2].params.Where("max_disparity").find("--set"), std::string::npos);
}

}  // namespace
}  // namespace attend
