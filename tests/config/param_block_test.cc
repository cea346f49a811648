#include "config/param_block.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>

#include "tests/support/error_message.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

using testing::ConfigErrorOf;
using testing::ErrorOf;
using testing::InputErrorOf;

TEST(ParamBlock, ReadsTypedValuesAndDefaults) {
  const ParamBlock block = ParamBlock::Parse(
      "a: 3\nb: 0.25\nc: text\nd: true\ne: [1, 2, 3]\nf: [x, y]\nnested: {k: 5}\n", "t.yaml");
  EXPECT_EQ(block.GetInt("a", 0), 3);
  EXPECT_DOUBLE_EQ(block.GetDouble("b", 0.0), 0.25);
  EXPECT_EQ(block.GetString("c", ""), "text");
  EXPECT_TRUE(block.GetBool("d", false));
  EXPECT_EQ(block.GetInts("e", {}), (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(block.GetStrings("f", {}), (std::vector<std::string>{"x", "y"}));
  EXPECT_EQ(block.Child("nested").GetInt("k", 0), 5);
  EXPECT_EQ(block.GetInt("absent", 42), 42);
  EXPECT_DOUBLE_EQ(block.GetDouble("a", 0.0), 3.0);  // an integer is a valid number
  EXPECT_NO_THROW(block.CheckNoUnknownKeys());
}

TEST(ParamBlock, UnknownKeyNamesKeyLineAndClosestKnownKey) {
  const ParamBlock block =
      ParamBlock::Parse("select:\n  min_area: 20\n  min_salency: 0.5\n", "cfg.yaml");
  const ParamBlock select = block.Child("select");
  select.GetInt("min_area", 0);
  select.GetDouble("min_saliency", 0.3);
  const std::string message = ConfigErrorOf([&] { select.CheckNoUnknownKeys(); });
  EXPECT_NE(message.find("cfg.yaml:3"), std::string::npos) << message;
  EXPECT_NE(message.find("unknown key 'min_salency' in select"), std::string::npos) << message;
  EXPECT_NE(message.find("did you mean 'min_saliency'"), std::string::npos) << message;
}

TEST(ParamBlock, WrongTypeAndOutOfRangeNameKeyAndLine) {
  const ParamBlock block = ParamBlock::Parse("x: 1\ny: abc\nz: -2\nw: 2.5\n", "c.yaml");
  std::string message = ConfigErrorOf([&] { block.GetDouble("y", 0.0); });
  EXPECT_NE(message.find("c.yaml:2: y: expected a number, got 'abc'"), std::string::npos)
      << message;
  message = ConfigErrorOf([&] { block.GetDouble("z", 0.0, Range::AtLeast(0)); });
  EXPECT_NE(message.find("c.yaml:3: z: value -2 out of range: must be >= 0"), std::string::npos)
      << message;
  message = ConfigErrorOf([&] { block.GetInt("w", 0); });
  EXPECT_NE(message.find("c.yaml:4: w: expected an integer"), std::string::npos) << message;
  message = ConfigErrorOf([&] { block.GetChoice("y", "fit", {"fit", "stretch", "native"}); });
  EXPECT_NE(message.find("'abc' is not one of fit, stretch, native"), std::string::npos) << message;
  message = ConfigErrorOf([&] { block.GetInts("x", {}); });
  EXPECT_NE(message.find("expected a list of integers"), std::string::npos) << message;
}

// YAML's infinities and not-a-number (.inf, -.Inf, .NaN) decode as numbers; no key takes one,
// whatever its range, in a scalar or in a list.
TEST(ParamBlock, NonFiniteNumbersAreRefusedWithKeyAndLine) {
  const ParamBlock block =
      ParamBlock::Parse("a: .inf\nb: -.Inf\nc: .NaN\nd: [1, .inf]\ne: 1e300\n", "n.yaml");
  std::string message = ConfigErrorOf([&] { block.GetDouble("a", 0.0, Range::AtLeast(0)); });
  EXPECT_NE(message.find("n.yaml:1: a: value .inf is not a finite number"), std::string::npos)
      << message;
  message = ConfigErrorOf([&] { block.GetDouble("b", 0.0); });
  EXPECT_NE(message.find("n.yaml:2: b: value -.Inf is not a finite number"), std::string::npos)
      << message;
  message = ConfigErrorOf([&] { block.GetDouble("c", 0.0); });
  EXPECT_NE(message.find("n.yaml:3: c: value .NaN is not a finite number"), std::string::npos)
      << message;
  message = ConfigErrorOf([&] { block.GetDoubles("d", {}); });
  EXPECT_NE(message.find("n.yaml:4: d: element 1 = .inf is not a finite number"),
            std::string::npos)
      << message;
  // A large finite number is a number.
  EXPECT_EQ(block.GetDouble("e", 0.0), 1e300);
}

TEST(ParamBlock, SyntaxErrorDuplicateKeyAndMissingFile) {
  std::string message = ConfigErrorOf([] { ParamBlock::Parse("a: [1, 2\nb: 3\n", "bad.yaml"); });
  EXPECT_NE(message.find("bad.yaml:"), std::string::npos) << message;
  EXPECT_NE(message.find("YAML syntax error"), std::string::npos) << message;
  message = ConfigErrorOf([] { ParamBlock::Parse("a: 1\nb: 2\na: 3\n", "dup.yaml"); });
  EXPECT_NE(message.find("dup.yaml:3: duplicate key 'a'"), std::string::npos) << message;
  message = ConfigErrorOf([] { ParamBlock::LoadFile("/nonexistent/attend.yaml"); });
  EXPECT_NE(message.find("/nonexistent/attend.yaml: the YAML file does not exist"), std::string::npos) << message;
  message = ConfigErrorOf([] { ParamBlock::Parse("- 1\n- 2\n", "list.yaml"); });
  EXPECT_NE(message.find("list.yaml:1: the top level must be a map"), std::string::npos) << message;
}

TEST(ParamBlock, TextThatIsNotUtf8OrHoldsAControlCharacterIsRefusedWithItsLine) {
  std::string message = ConfigErrorOf([] { ParamBlock::Parse("a: 1\nb: \xE9t\xE9\n", "x.yaml"); });
  EXPECT_NE(message.find("x.yaml:2: not valid UTF-8 (byte 8)"), std::string::npos) << message;
  message = ConfigErrorOf(
      [] { ParamBlock::Parse(std::string("a: 1\nb: 2\n{c: 1, d\0_e: 2}\n", 26), "n.yaml"); });
  EXPECT_NE(message.find("n.yaml:3: a control character (byte 18)"), std::string::npos) << message;
  message = ConfigErrorOf([] { ParamBlock::Parse("a: \x1b[31m\n", "esc.yaml"); });
  EXPECT_NE(message.find("esc.yaml:1: a control character (byte 3)"), std::string::npos) << message;
  // Tabs, line ends and characters beyond ASCII are text.
  const ParamBlock block = ParamBlock::Parse("a: \"\tx\"\r\nb: caf\xC3\xA9\n", "ok.yaml");
  EXPECT_EQ(block.GetString("b", ""), "caf\xC3\xA9");
  ParamBlock root = ParamBlock::Parse("a: 1\n", "ok.yaml");
  message = ConfigErrorOf([&] { root.Override(std::string("a=\x07", 3)); });
  EXPECT_NE(message.find("--set: a control character"), std::string::npos) << message;
}

TEST(ParamBlock, LoadFileReportsTheFilePath) {
  testing::TempDir dir;
  const std::string path = dir.Write("c.yaml", "k: 1\nq: nope\n");
  const ParamBlock block = ParamBlock::LoadFile(path);
  const std::string message = ConfigErrorOf([&] { block.GetBool("q", false); });
  EXPECT_NE(message.find(path + ":2: q: expected true or false"), std::string::npos) << message;
}

TEST(ParamBlock, OverrideParsesValueAsYamlAndIsNamedInErrors) {
  ParamBlock block = ParamBlock::Parse("output:\n  dump: []\n  every: 1\n", "c.yaml");
  block.Override("output.dump=[features,saliency]");
  block.Override("output.every=abc");
  block.Override("select.max_new=3");  // creates keys that were absent
  const ParamBlock output = block.Child("output");
  EXPECT_EQ(output.GetStrings("dump", {}), (std::vector<std::string>{"features", "saliency"}));
  const std::string message = ConfigErrorOf([&] { output.GetInt("every", 1); });
  EXPECT_NE(message.find("--set output.every=abc: output.every: expected an integer"),
            std::string::npos)
      << message;
  EXPECT_EQ(block.Child("select").GetInt("max_new", 0), 3);
  // An override of a key that no reader knows is reported as unknown, at the --set.
  block.Override("output.evry=2");
  output.GetStrings("dump", {});
  const std::string unknown = ConfigErrorOf([&] { block.Child("output").CheckNoUnknownKeys(); });
  EXPECT_NE(unknown.find("--set output.evry=2: unknown key 'evry'"), std::string::npos) << unknown;
}

TEST(ParamBlock, OverrideAddressesListElementsByIndexOrName) {
  ParamBlock block = ParamBlock::Parse(
      "features:\n  - {name: colour_contrast, weight: 1.0}\n  - {name: skin, weight: 1.0}\n",
      "c.yaml");
  block.Override("features.skin.weight=0.5");
  block.Override("features.0.weight=2");
  const std::vector<ParamBlock> features = block.Children("features");
  ASSERT_EQ(features.size(), 2u);
  EXPECT_DOUBLE_EQ(features[0].GetDouble("weight", 0), 2.0);
  EXPECT_DOUBLE_EQ(features[1].GetDouble("weight", 0), 0.5);
  EXPECT_EQ(features[1].path(), "features.1");
  std::string message = ConfigErrorOf([&] { block.Override("features.skn.weight=1"); });
  EXPECT_NE(message.find("no element named 'skn' (did you mean 'skin'?)"), std::string::npos)
      << message;
  message = ConfigErrorOf([&] { block.Override("features.5.weight=1"); });
  EXPECT_NE(message.find("the list has 2 elements"), std::string::npos) << message;
  message = ConfigErrorOf([&] { block.Override("novalue"); });
  EXPECT_NE(message.find("expected KEY.PATH=VALUE"), std::string::npos) << message;
}

TEST(ParamBlock, RequiredKeysAndListSizes) {
  const ParamBlock block = ParamBlock::Parse("size: [320, 240, 3]\n", "s.yaml");
  std::string message = ConfigErrorOf([&] { block.RequireDouble("focal_px"); });
  EXPECT_NE(message.find("focal_px: required key is missing"), std::string::npos) << message;
  message = ConfigErrorOf([&] { block.GetInts("size", {}, Range::Above(0), 2); });
  EXPECT_NE(message.find("expected 2 elements, got 3"), std::string::npos) << message;
}

TEST(Range, DescribesAndContains) {
  EXPECT_TRUE(Range::Closed(0, 1).Contains(1));
  EXPECT_FALSE(Range::Above(0).Contains(0));
  EXPECT_FALSE(Range::Any().Contains(std::numeric_limits<double>::quiet_NaN()));
  EXPECT_EQ(Range::Closed(0, 1).Describe(), "must be in [0, 1]");
  EXPECT_EQ(Range::Above(0).Describe(), "must be > 0");
}

TEST(ParamBlock, FailCheckPutsAnOptionsErrorAtTheKeyItNames) {
  const ParamBlock block = ParamBlock::Parse("a: 1\nwindow: 4\n", "c.yaml");
  std::string message = ConfigErrorOf([&] { block.FailCheck("window must be odd"); });
  EXPECT_EQ(message, "c.yaml:2: window: must be odd");
  message = ConfigErrorOf([&] { block.FailCheck("scales: each must be in (0, 200]"); });
  EXPECT_EQ(message, "c.yaml:1: scales: each must be in (0, 200]");  // no such key: the block
}

TEST(Range, DescribesTheBoundAValueBreaks) {
  const Range range = Range::AboveUpTo(0, 1);
  EXPECT_EQ(range.DescribeBreach(0.0), "must be > 0");
  EXPECT_EQ(range.DescribeBreach(2.0), "must be <= 1");
  EXPECT_EQ(Range::Closed(1, 5).DescribeBreach(0.0), "must be >= 1");
  EXPECT_EQ(Range::Closed(1, 5).DescribeBreach(std::nan("")), "must be in [1, 5]");
  // A float field's bounds, rounded to float: 0.01f is below 0.01.
  EXPECT_TRUE(Range::Closed(0.01, 1).RoundedToFloat().Contains(static_cast<float>(0.01)));
  EXPECT_FALSE(Range::Closed(0.01, 1).Contains(static_cast<float>(0.01)));
}

// A count of up to 64 bits, read as text: all of uint64's range, errors at the key's line.
TEST(ParamBlock, ReadsCountsOfSixtyFourBits) {
  const ParamBlock block =
      ParamBlock::Parse("seed: 18446744073709551615\nn: 12\nbad: -3\nlist: [1]\n", "c.yaml");
  EXPECT_EQ(block.GetCount("seed", 0, UINT64_MAX), UINT64_MAX);
  EXPECT_EQ(block.GetCount("n", 0, 100), 12u);
  EXPECT_EQ(block.GetCount("absent", 5, 100), 5u);
  EXPECT_EQ(ConfigErrorOf([&] { block.GetCount("n", 0, 10); }),
            "c.yaml:2: n: expected an integer in [0, 10], got '12'");
  EXPECT_EQ(ConfigErrorOf([&] { block.GetCount("bad", 0, 10); }),
            "c.yaml:3: bad: expected an integer in [0, 10], got '-3'");
  EXPECT_EQ(ConfigErrorOf([&] { block.GetCount("list", 0, 10); }),
            "c.yaml:4: list: expected an integer in [0, 10], got a list");
}

// Values passed on as YAML text (a sweep's --set values), each with where it was written.
TEST(ParamBlock, GivesValuesAsFlowTextWithTheirLines) {
  ParamBlock block = ParamBlock::Parse(
      "grid:\n  a.b: [1, 2.5, {x: 1}]\n  c:\n    - [3, 4]\n    - text\nscalar: 7\n", "s.yaml");
  const ParamBlock grid = block.Child("grid");
  EXPECT_TRUE(grid.IsList("a.b"));
  EXPECT_FALSE(grid.IsMap("a.b"));
  EXPECT_FALSE(grid.IsList("missing"));
  const std::vector<ParamBlock::Text> values = grid.ElementTexts("a.b");
  ASSERT_EQ(values.size(), 3u);
  EXPECT_EQ(values[0].text, "1");
  EXPECT_EQ(values[1].text, "2.5");
  EXPECT_EQ(values[2].text, "{x: 1}");
  EXPECT_EQ(values[2].where, "s.yaml:2");
  const std::vector<ParamBlock::Text> c = grid.ElementTexts("c");
  ASSERT_EQ(c.size(), 2u);
  EXPECT_EQ(c[0].text, "[3, 4]");
  EXPECT_EQ(c[0].where, "s.yaml:4");
  EXPECT_EQ(c[1].where, "s.yaml:5");
  grid.CheckNoUnknownKeys();
  EXPECT_EQ(block.ValueText("scalar").text, "7");
  EXPECT_EQ(block.ValueText("scalar").where, "s.yaml:6");
  EXPECT_EQ(ConfigErrorOf([&] { block.ElementTexts("scalar"); }),
            "s.yaml:6: scalar: expected a list, got '7'");
  EXPECT_NE(ConfigErrorOf([&] { block.ValueText("none"); }).find(": none: required key is missing"),
            std::string::npos);
  block.Override("scalar=[8, 9]");
  const std::vector<ParamBlock::Text> set = block.ElementTexts("scalar");
  ASSERT_EQ(set.size(), 2u);
  EXPECT_EQ(set[1].text, "9");
  EXPECT_EQ(set[1].where, "--set scalar=[8, 9]");
}

}  // namespace
}  // namespace attend
