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

template <typename Body>
std::string testing_error(Body body) {
  try {
    body();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

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

struct Numbers {
  std::vector<double> scales = {2, 4};
  double width = 1, height = 2;
  std::int64_t samples = 0;
  std::uint64_t seed = 7;

  static const OptionFields<Numbers>& Fields() {
    static const OptionFields<Numbers> fields = {
        {"scales", &Numbers::scales, Range::AboveUpTo(0, 10), ""},
        {"size",
         NumbersMember<Numbers>{[](const Numbers& n) { return std::vector<double>{n.width, n.height}; },
                                [](Numbers* n, const std::vector<double>& v) {
                                  n->width = v[0];
                                  n->height = v[1];
                                },
                                2},
         Range::Above(0), ""},
        {"samples", &Numbers::samples, Range::Any(), ""},
        {"seed", &Numbers::seed, Range::Closed(0, 100), ""}};
    return fields;
  }
};

std::string NumbersErrorOf(const std::string& yaml) {
  try {
    Numbers numbers;
    ReadFields(ParamBlock::Parse(yaml, "n.yaml"), Numbers::Fields(), &numbers);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ReadFields, ReadsListsOfNumbersAndCounts) {
  const ParamBlock block = ParamBlock::Parse(
      "scales: [1, 2.5, 10]\nsize: [3, 4]\nsamples: 9000000000\nseed: 100\n", "n.yaml");
  Numbers numbers;
  ReadFields(block, Numbers::Fields(), &numbers);
  EXPECT_EQ(numbers.scales, (std::vector<double>{1, 2.5, 10}));
  EXPECT_EQ(numbers.width, 3);
  EXPECT_EQ(numbers.height, 4);
  EXPECT_EQ(numbers.samples, 9000000000);
  EXPECT_EQ(numbers.seed, 100u);
  block.CheckNoUnknownKeys();
  // Absent keys keep the struct's values.
  Numbers defaults;
  ReadFields(ParamBlock::Parse("{}", "n.yaml"), Numbers::Fields(), &defaults);
  EXPECT_EQ(defaults.width, 1);
  EXPECT_EQ(defaults.seed, 7u);

  EXPECT_NE(NumbersErrorOf("scales: [1, 11]\n").find("n.yaml:1: scales: element 1 = 11 out of range"),
            std::string::npos);
  EXPECT_NE(NumbersErrorOf("size: [1, 2, 3]\n").find("n.yaml:1: size: expected 2 elements, got 3"),
            std::string::npos);
  // Within an int's range a 64-bit field reads as an int, with an int's messages.
  EXPECT_NE(NumbersErrorOf("\nseed: 101\n").find("n.yaml:2: seed: value 101 out of range: must be "
                                                 "in [0, 100]"),
            std::string::npos)
      << NumbersErrorOf("\nseed: 101\n");
  EXPECT_NE(NumbersErrorOf("samples: -1\n").find("samples: expected an integer in [0, "
                                                 "9223372036854775807], got '-1'"),
            std::string::npos);
}

TEST(ReadFields, ChecksAndDescribesListsOfNumbers) {
  Numbers numbers;
  EXPECT_EQ(CheckFieldRanges(numbers, Numbers::Fields()), "");
  numbers.scales = {1, 0};
  EXPECT_EQ(CheckFieldRanges(numbers, Numbers::Fields()), "scales each must be > 0, got 0");
  numbers = Numbers();
  numbers.height = -1;
  EXPECT_EQ(CheckFieldRanges(numbers, Numbers::Fields(), ": "), "size: each must be > 0, got -1");
  const std::vector<FieldDescription> lines = DescribeFields(Numbers::Fields());
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0].type, "numbers");
  EXPECT_EQ(lines[0].fallback, "[2, 4]");
  EXPECT_EQ(lines[1].type, "2 numbers");
  EXPECT_EQ(lines[1].fallback, "[1, 2]");
  EXPECT_EQ(lines[3].type, "int");
  EXPECT_EQ(lines[3].fallback, "7");
}

TEST(ReadFields, SectionsAndListsOfBlocksHaveTheirOwnTables) {
  const ParamBlock root = ParamBlock::Parse(
      "inner: {count: 4}\nitems:\n  - {count: 2, rate: 0.5}\n  - {count: 1}\n", "s.yaml");
  Sample inner;
  ReadSection(root, "inner", Sample::Fields(), &inner);
  EXPECT_EQ(inner.count, 4);
  Sample start;
  start.rate = 0.25;
  int checked = 0;
  const std::vector<Sample> items =
      ReadList(root, "items", Sample::Fields(), start,
               [&](const ParamBlock&, const Sample&, const std::vector<Sample>& before) {
                 EXPECT_EQ(before.size(), static_cast<size_t>(checked));
                 ++checked;
               });
  ASSERT_EQ(items.size(), 2u);
  EXPECT_EQ(items[0].count, 2);
  EXPECT_EQ(items[0].rate, 0.5);
  EXPECT_EQ(items[1].rate, 0.25);  // from `start`
  root.CheckNoUnknownKeys();
  // A key a section's table does not name: unknown, at its line, in the section.
  const std::string message = testing_error([] {
    Sample sample;
    ReadSection(ParamBlock::Parse("inner:\n  cuont: 3\n", "s.yaml"), "inner", Sample::Fields(),
                &sample);
  });
  EXPECT_NE(message.find("s.yaml:2: unknown key 'cuont' in inner (did you mean 'count'?)"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace attend
