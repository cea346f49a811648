#include "util/strings.h"

#include <gtest/gtest.h>

namespace attend {
namespace {

TEST(Strings, EditDistanceKnownValues) {
  EXPECT_EQ(EditDistance("", ""), 0);
  EXPECT_EQ(EditDistance("abc", ""), 3);
  EXPECT_EQ(EditDistance("kitten", "sitting"), 3);
  EXPECT_EQ(EditDistance("max_targets", "max_target"), 1);
  EXPECT_EQ(EditDistance("weight", "wieght"), 2);
}

TEST(Strings, ClosestMatchPicksNearestAndRejectsFarWords) {
  const std::vector<std::string> keys = {"min_area", "min_saliency", "max_new", "max_targets"};
  EXPECT_EQ(ClosestMatch("min_salency", keys), "min_saliency");
  EXPECT_EQ(ClosestMatch("max_target", keys), "max_targets");
  EXPECT_EQ(ClosestMatch("colour", keys), "");
  EXPECT_EQ(DidYouMean("max_nwe", keys), " (did you mean 'max_new'?)");
  EXPECT_EQ(DidYouMean("zzzzzzzz", keys), "");
}

TEST(Strings, SplitKeepsEmptyFieldsAndJoinInverts) {
  EXPECT_EQ(Split("a,,b", ','), (std::vector<std::string>{"a", "", "b"}));
  EXPECT_EQ(Split("", ','), (std::vector<std::string>{""}));
  EXPECT_EQ(Join(Split("x.y.z", '.'), "."), "x.y.z");
}

TEST(Strings, NonPrintableAtFindsWhatYamlDoesNotAllow) {
  EXPECT_EQ(NonPrintableAt("plain text\twith tab\r\n"), std::string_view::npos);
  EXPECT_EQ(NonPrintableAt(std::string_view("ab\0c", 4)), 2u);
  EXPECT_EQ(NonPrintableAt("a\x7f"), 1u);
  EXPECT_EQ(NonPrintableAt("x\xC2\x9F"), 1u);                               // U+009F, a C1 control
  EXPECT_EQ(NonPrintableAt("x\xC2\x85 \xC2\xA0"), std::string_view::npos);  // NEL, NBSP
}

}  // namespace
}  // namespace attend
