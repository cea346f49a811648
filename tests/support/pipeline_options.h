// Options and feature setups for pipeline tests: the configuration's `features:` list from
// YAML, as a file would give it, over the defaults.
#pragma once

#include <string>

#include "config/feature_list.h"
#include "features/feature_map.h"
#include "pipeline/attend_options.h"
#include "tests/support/temp_dir.h"

namespace attend::testing {

inline AttendOptions WithFeatures(const std::string& features) {
  AttendOptions options;
  options.features =
      ReadFeatureList(ParamBlock::Parse("features: " + features, "test.yaml"), "features");
  return options;
}

// A setup for a stereo or monocular source, with the source tree as home.
inline FeatureSetup SetupFor(bool stereo) {
  FeatureSetup setup;
  setup.stereo = stereo;
  setup.home = ProjectRoot();
  return setup;
}

}  // namespace attend::testing
