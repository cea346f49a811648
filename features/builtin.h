// The built-in feature plugins, registered in one list (features/builtin.cc); configs/README.md
// documents each one's parameters.
#pragma once

#include "features/feature_map.h"

namespace attend {

// A registry holding every built-in feature.
FeatureRegistry BuiltinFeatures();

}  // namespace attend
