// The ranges of the configuration's numeric keys are written once, in the options structs
// (util/option_fields.h): for every listed field, a value just outside its range is refused
// both by the configuration, naming the key and its line, and by the struct's Check().
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdlib>

#include "features/skin.h"
#include "io/sequence.h"
#include "pipeline/options_io.h"
#include "pyramid/segmentation.h"
#include "saliency/saliency.h"
#include "semiattentive/attention.h"
#include "tests/support/error_message.h"
#include "tracker/target_tracker.h"
#include "tracker/tracker.h"
#include "util/option_fields.h"

namespace attend {
namespace {

// Values just below and just above `range` (none where it is unbounded); whole numbers for an
// int field.
std::vector<double> Outside(const Range& range, bool whole) {
  std::vector<double> values;
  if (std::isfinite(range.min)) {
    values.push_back(range.min_open ? range.min
                                    : range.min - (whole ? 1.0 : std::max(1e-4, range.min / 2)));
  }
  if (std::isfinite(range.max)) {
    values.push_back(range.max_open ? range.max : range.max + (whole ? 1.0 : range.max / 2));
  }
  return values;
}

// Every numeric field of `fields`, bound to the key `prefix + name`: each value outside its range is a
// configuration error at that key, and Check() of `whole` (the struct holding the fields, set
// through `at`) refuses it too. The fields' own struct accepts its float bounds as stored.
template <typename Options, typename Whole, typename At>
void ExpectRangesAppliedBothWays(const std::string& prefix, const OptionFields<Options>& fields,
                                 At at) {
  for (const OptionField<Options>& field : fields) {
    const std::string key = prefix + std::string(field.name);
    std::visit(
        [&](auto member) {
          using M = decltype(member);
          if constexpr (std::is_member_object_pointer_v<M>) {
          using T = std::remove_cvref_t<decltype(std::declval<Options>().*member)>;
          if constexpr (std::is_arithmetic_v<T> && !std::is_same_v<T, bool>) {
          for (const double value : Outside(field.range, std::is_same_v<T, int>)) {
            const std::string text = ShortestNumber(value);
            const std::string message = testing::ConfigErrorOf([&] {
              ReadOptions(ParamBlock::Parse(key.substr(0, key.find('.')) + ": {" +
                                                key.substr(key.find('.') + 1) + ": " + text + "}",
                                            "r.yaml"));
            });
            EXPECT_NE(message.find("r.yaml:1: " + key + ": value " + text + " out of range"),
                      std::string::npos)
                << key << " = " << text << ": " << message;
            Whole whole;
            at(&whole)->*member = static_cast<T>(value);
            EXPECT_NE(whole.Check(), "") << key << " = " << text << ": Check() accepts it";
          }
          if constexpr (std::is_same_v<T, float>) {
            Options options;
            if (!field.range.min_open && std::isfinite(field.range.min)) {
              options.*member = static_cast<float>(field.range.min);
              EXPECT_EQ(CheckFieldRanges(options, fields), "") << key << " at its minimum";
            }
          }
          }
          }
        },
        field.member);
  }
}

TEST(OptionRanges, EveryRangedKeyIsRefusedOutsideItsRangeByTheFileAndByCheck) {
  ExpectRangesAppliedBothWays<SequenceOptions, SequenceOptions>(
      "sequence.", SequenceOptions::Fields(), [](SequenceOptions* o) { return o; });
  ExpectRangesAppliedBothWays<SourceSpec, SequenceOptions>(
      "sequence.", SourceSpec::Fields(), [](SequenceOptions* o) { return &o->source; });
  ExpectRangesAppliedBothWays<LiveOptions, SequenceOptions>(
      "live.", LiveOptions::Fields(), [](SequenceOptions* o) { return &o->source.live; });
  ExpectRangesAppliedBothWays<SegmentationOptions, SegmentationOptions>(
      "segmentation.", SegmentationOptions::Fields(), [](SegmentationOptions* o) { return o; });
  ExpectRangesAppliedBothWays<SaliencyOptions, SaliencyOptions>(
      "saliency.", SaliencyOptions::Fields(), [](SaliencyOptions* o) { return o; });
  ExpectRangesAppliedBothWays<SelectOptions, AttentionOptions>(
      "select.", SelectOptions::Fields(), [](AttentionOptions* o) { return &o->select; });
  ExpectRangesAppliedBothWays<AttentionOptions, AttentionOptions>(
      "select.", AttentionOptions::Fields(), [](AttentionOptions* o) { return o; });
  ExpectRangesAppliedBothWays<SkinRegionOptions, AttentionOptions>(
      "select.skin_", SkinRegionOptions::Fields(),
      [](AttentionOptions* o) { return &o->skin_region; });
  ExpectRangesAppliedBothWays<DropOptions, AttentionOptions>(
      "drop.", DropOptions::Fields(), [](AttentionOptions* o) { return &o->drop; });
  ExpectRangesAppliedBothWays<InhibitionOptions, AttentionOptions>(
      "inhibition.", InhibitionOptions::Fields(),
      [](AttentionOptions* o) { return &o->inhibition; });
  ExpectRangesAppliedBothWays<ObjectFileOptions, AttentionOptions>(
      "attention.", ObjectFileOptions::Fields(), [](AttentionOptions* o) { return &o->memory; });
  ExpectRangesAppliedBothWays<TrackerOptions, AttentionOptions>(
      "tracker.", TrackerOptions::Fields(), [](AttentionOptions* o) { return &o->tracker.bip; });
  ExpectRangesAppliedBothWays<OpenCvTrackerOptions, TargetTrackerOptions>(
      "tracker.", OpenCvTrackerOptions::Fields(), [](TargetTrackerOptions* o) {
        o->kind = TrackerKind::kKcf;  // Check() checks the options of the chosen kind
        return &o->opencv;
      });
}

// Every numeric key of the configuration has a range: a number far outside any is refused at
// its key. The numeric keys are those the writer emits as plain numbers.
TEST(OptionRanges, EveryNumericKeyOfTheConfigurationHasARange) {
  const YAML::Node root = YAML::Load(OptionsToYaml(AttendOptions()));
  int numeric = 0;
  const auto check = [&](const std::string& section, const std::string& key) {
    for (const std::string value : {"2000000000", "-2000000000"}) {
      const std::string yaml =
          section.empty() ? key + ": " + value : section + ": {" + key + ": " + value + "}";
      const std::string path = section.empty() ? key : section + "." + key;
      const std::string message =
          testing::ConfigErrorOf([&] { ReadOptions(ParamBlock::Parse(yaml, "n.yaml")); });
      EXPECT_NE(message.find(path + ": value " + value + " out of range"), std::string::npos)
          << path << ": " << message;
    }
    ++numeric;
  };
  const auto is_number = [](const YAML::Node& node) {
    if (!node.IsScalar() || node.Tag() != "?") return false;  // quoted: a string
    char* end = nullptr;
    const std::string& text = node.Scalar();
    std::strtod(text.c_str(), &end);
    return !text.empty() && *end == '\0';
  };
  for (const auto& entry : root) {
    const std::string name = entry.first.Scalar();
    if (entry.second.IsMap()) {
      for (const auto& field : entry.second) {
        if (is_number(field.second)) check(name, field.first.Scalar());
      }
    } else if (is_number(entry.second)) {
      check("", name);
    }
  }
  // sequence 7, live 3, segmentation 3, saliency 3, select 30, drop 4, inhibition 1,
  // attention 9 (6 of the object files, 3 of the appearance network), depth 8, tracker 47 (24
  // of the template modes and the OpenCV kinds, 23 of the correlation mode), threads: so that
  // a writer change that hid the numbers fails here.
  EXPECT_EQ(numeric, 116);
}

}  // namespace
}  // namespace attend
