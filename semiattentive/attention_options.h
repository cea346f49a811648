// The options of the attention stage (semiattentive/attention.h): one struct per section of
// the configuration, each beside the step that reads it (select_options.h, release.h,
// inhibition.h, object_files.h; the tracker's in tracker/target_tracker.h), and the stage's own
// fields (the `select` keys label_overlap and skin_*).
#pragma once

#include <string>

#include "features/skin.h"
#include "semiattentive/inhibition.h"
#include "semiattentive/object_files.h"
#include "semiattentive/reidentification.h"
#include "semiattentive/release.h"
#include "semiattentive/select_options.h"
#include "semiattentive/target_depth.h"
#include "tracker/target_tracker.h"
#include "util/option_fields.h"

namespace attend {

struct AttentionOptions {
  SelectOptions select;
  DropOptions drop;
  InhibitionOptions inhibition;
  TargetTrackerOptions tracker;  // the kind and its options (tracker/target_tracker.h)
  // A target is a skin target when at least this share of its colour region is skin, by the
  // skin model in `skin_model` (a file as made by attend skin-train).
  float skin_fraction = 0.5f;
  std::string skin_model = "configs/skin_tsl.yaml";
  // Whether a mostly-skin region must also be confident, skin-shaped skin to start a skin
  // target (false: the thesis's rule, the share alone), and the bounds of that test.
  bool skin_check = true;
  SkinRegionOptions skin_region;
  // Object files: the memory of objects that ended (semiattentive/object_files.h); off when
  // memory.memory_frames is 0.
  ObjectFileOptions memory;
  // What targets look like: a re-identification network's embedding beside the colour
  // histogram and grey template (semiattentive/reidentification.h); none by default.
  AppearanceOptions appearance;
  // Each target's disparity and depth in the loop (the depth section; target_depth.h).
  DepthOptions depth;
  // A target takes the label of a top-down detection ("person", "face") whose box and its own
  // overlap by at least this share of the larger of the two.
  float label_overlap = 0.5f;
  // "" when valid; otherwise names the field and the broken constraint.
  std::string Check() const;
  // This struct's own fields (the `select` keys label_overlap, skin_*).
  static const OptionFields<AttentionOptions>& Fields();
};

}  // namespace attend
