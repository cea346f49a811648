#include "semiattentive/attention_options.h"

namespace attend {

const OptionFields<AttentionOptions>& AttentionOptions::Fields() {
  using O = AttentionOptions;
  static const OptionFields<AttentionOptions> fields = {
      {"label_overlap", &O::label_overlap, Range::Closed(0, 1),
       "a target takes a detection's label when their boxes overlap by this share"},
      {"skin_fraction", &O::skin_fraction, Range::Closed(0, 1),
       "a target is a skin target when this share of its region is skin"},
      {"skin_model", &O::skin_model, "the skin model file (attend skin-train)"},
      {"skin_check", &O::skin_check,
       "a skin target's region must also be confident, skin-shaped skin"}};
  return fields;
}

std::string AttentionOptions::Check() const {
  std::string error = CheckFieldRanges(select, SelectOptions::Fields());
  if (!error.empty()) return "select." + error;
  error = CheckFieldRanges(drop, DropOptions::Fields());
  if (!error.empty()) return "drop." + error;
  error = CheckFieldRanges(inhibition, InhibitionOptions::Fields());
  if (!error.empty()) return "inhibition." + error;
  error = CheckFieldRanges(*this, Fields());
  if (!error.empty()) return error;
  error = skin_region.Check();
  if (!error.empty()) return "select.skin_region: " + error;
  error = tracker.Check();
  if (!error.empty()) return "tracker." + error;
  error = appearance.Check();
  if (!error.empty()) return "attention." + error;
  error = depth.Check();
  if (!error.empty()) return "depth." + error;
  error = memory.Check();
  if (!error.empty()) return "attention." + error;
  return "";
}

}  // namespace attend
