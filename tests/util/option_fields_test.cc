// The field table of an options struct (util/option_fields.h): ranges and choices checked,
// every field described with its default, enum fields read and written by their names.
#include "util/option_fields.h"

#include <gtest/gtest.h>

#include "util/enum_table.h"

namespace attend {
namespace {

enum class Shade { kLight, kDark };
constexpr EnumTable<Shade, 2> kShades = {{{{Shade::kLight, "light"}, {Shade::kDark, "dark"}}}};

const std::vector<std::string>& Sizes() {
  static const std::vector<std::string> sizes = {"small", "large"};
  return sizes;
}

struct Sample {
  int count = 3;
  float rate = 0.2f;
  bool on = true;
  std::string size = "small";
  std::vector<std::string> tags = {"a"};
  Shade shade = Shade::kDark;
  int bound = 64;

  static const OptionFields<Sample>& Fields() {
    static const OptionFields<Sample> fields = {
        {"count", &Sample::count, Range::Closed(1, 10), "how many"},
        {"rate", &Sample::rate, Range::AboveUpTo(0, 1), "how fast"},
        {"on", &Sample::on, "whether"},
        {"size", &Sample::size, "which size", &Sizes},
        {"tags", &Sample::tags, "labels"},
        {"shade", EnumField<&Sample::shade, kShades>(), "light or dark"},
        CodeOnly<Sample>({"bound", &Sample::bound, Range::AtLeast(1), "a safety bound"})};
    return fields;
  }
};

TEST(OptionFields, RangesAndChoicesAreCheckedInTableOrder) {
  Sample sample;
  EXPECT_EQ(CheckFieldRanges(sample, Sample::Fields()), "");
  sample.count = 11;
  EXPECT_EQ(CheckFieldRanges(sample, Sample::Fields()), "count must be <= 10, got 11");
  sample.count = 3;
  sample.rate = 0.f;
  EXPECT_EQ(CheckFieldRanges(sample, Sample::Fields(), ": "), "rate: must be > 0, got 0");
  sample.rate = 0.5f;
  sample.size = "smal";
  EXPECT_EQ(CheckFieldRanges(sample, Sample::Fields()),
            "size must be one of small, large, got 'smal' (did you mean 'small'?)");
  sample.size = "large";
  sample.bound = 0;  // code-only fields are checked too
  EXPECT_EQ(CheckFieldRanges(sample, Sample::Fields()), "bound must be >= 1, got 0");
}

TEST(OptionFields, EveryFieldIsDescribedWithItsDefault) {
  const std::vector<FieldDescription> lines = DescribeFields(Sample::Fields());
  ASSERT_EQ(lines.size(), 7u);
  EXPECT_EQ(lines[0].type, "int");
  EXPECT_EQ(lines[0].range, "must be in [1, 10]");
  EXPECT_EQ(lines[1].fallback, "0.2");  // the float as written, not 0.200000003
  EXPECT_EQ(lines[2].type, "bool");
  EXPECT_EQ(lines[2].fallback, "true");
  EXPECT_EQ(lines[3].type, "small|large");
  EXPECT_EQ(lines[3].fallback, "\"small\"");
  EXPECT_EQ(lines[4].fallback, "[a]");
  EXPECT_EQ(lines[5].type, "light|dark");
  EXPECT_EQ(lines[5].fallback, "dark");
  EXPECT_EQ(lines[5].doc, "light or dark");
  const std::string text = FormatFieldDescriptions(lines, "s.");
  EXPECT_NE(text.find("  s.count  int in [1, 10], default 3: how many\n"), std::string::npos)
      << text;
}

TEST(OptionFields, EnumFieldsGoThroughTheirTableAndFieldsCompare) {
  Sample a, b;
  const auto& shade = std::get<EnumMember<Sample>>(FieldNamed(Sample::Fields(), "shade").member);
  EXPECT_EQ(shade.get(a), "dark");
  EXPECT_TRUE(shade.set(&a, "light"));
  EXPECT_EQ(a.shade, Shade::kLight);
  EXPECT_FALSE(shade.set(&a, "grey"));
  EXPECT_EQ(a.shade, Shade::kLight);
  EXPECT_FALSE(SameFields(a, b, Sample::Fields()));
  a.shade = Shade::kDark;
  EXPECT_TRUE(SameFields(a, b, Sample::Fields()));
  EXPECT_EQ(FindField(a, Sample::Fields(), &a.rate)->name, "rate");
  EXPECT_EQ(FindField(a, Sample::Fields(), &a.shade)->name, "shade");
  EXPECT_TRUE(HasKey(Sample::Fields(), "tags"));
  EXPECT_FALSE(HasKey(Sample::Fields(), "bound"));  // code only
}

}  // namespace
}  // namespace attend
