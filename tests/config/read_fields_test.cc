// ReadFields (config/read_fields.h): each field of a table read from a block by its type,
// with its range or choices, errors at the key's line, code-only fields never read.
#include "config/read_fields.h"

#include <gtest/gtest.h>

#include "util/enum_table.h"
#include "util/error.h"

namespace attend {
namespace {

enum class Shade { kLight, kDark };
constexpr EnumTable<Shade, 2> kShades = {{{{Shade::kLight, "light"}, {Shade::kDark, "dark"}}}};

const std::vector<std::string>& Kinds() {
  static const std::vector<std::string> kinds = {"x", "y"};
  return kinds;
}

struct Sample {
  int count = 3;
  double rate = 0.5;
  bool on = false;
  std::string name = "n";
  std::vector<std::string> kinds = {"x"};
  Shade shade = Shade::kDark;
  int bound = 64;

  static const OptionFields<Sample>& Fields() {
    static const OptionFields<Sample> fields = {
        {"count", &Sample::count, Range::Closed(1, 10), ""},
        {"rate", &Sample::rate, Range::Closed(0, 1), ""},
        {"on", &Sample::on, ""},
        {"name", &Sample::name, ""},
        {"kinds", &Sample::kinds, "", &Kinds},
        {"shade", EnumField<&Sample::shade, kShades>(), ""},
        CodeOnly<Sample>({"bound", &Sample::bound, Range::AtLeast(1), ""})};
    return fields;
  }
};

std::string ErrorOf(const std::string& yaml) {
  try {
    const ParamBlock block = ParamBlock::Parse(yaml, "f.yaml");
    Sample sample;
    ReadFields(block, Sample::Fields(), &sample, "s_");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ReadFields, ReadsEveryKindOfFieldWithAPrefix) {
  const ParamBlock block = ParamBlock::Parse(
      "s_count: 7\ns_rate: 0.25\ns_on: true\ns_name: m\ns_kinds: [y, x]\ns_shade: light\n",
      "f.yaml");
  Sample sample;
  ReadFields(block, Sample::Fields(), &sample, "s_");
  EXPECT_EQ(sample.count, 7);
  EXPECT_EQ(sample.rate, 0.25);
  EXPECT_TRUE(sample.on);
  EXPECT_EQ(sample.name, "m");
  EXPECT_EQ(sample.kinds, (std::vector<std::string>{"y", "x"}));
  EXPECT_EQ(sample.shade, Shade::kLight);
  block.CheckNoUnknownKeys();
  EXPECT_EQ(
      FieldKeys(Sample::Fields(), "s_"),
      (std::vector<std::string>{"s_count", "s_rate", "s_on", "s_name", "s_kinds", "s_shade"}));
}

TEST(ReadFields, ErrorsNameTheKeyAndItsLine) {
  EXPECT_NE(ErrorOf("s_on: true\ns_count: 11\n").find("f.yaml:2: s_count: value 11 out of range"),
            std::string::npos)
      << ErrorOf("s_on: true\ns_count: 11\n");
  EXPECT_NE(ErrorOf("s_shade: drak\n").find("f.yaml:1: s_shade: 'drak' is not one of light, dark"),
            std::string::npos)
      << ErrorOf("s_shade: drak\n");
  EXPECT_NE(ErrorOf("s_kinds: [x, z]\n").find("f.yaml:1: s_kinds: 'z' is not one of x, y"),
            std::string::npos)
      << ErrorOf("s_kinds: [x, z]\n");
  // A code-only field is not a key: naming it is an unknown key.
  const ParamBlock block = ParamBlock::Parse("s_bound: 3\n", "f.yaml");
  Sample sample;
  ReadFields(block, Sample::Fields(), &sample, "s_");
  EXPECT_EQ(sample.bound, 64);
  EXPECT_THROW(block.CheckNoUnknownKeys(), ConfigError);
}

}  // namespace
}  // namespace attend
