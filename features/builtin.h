// The built-in feature plugins, in one table (features/builtin.cc): each row a feature's name,
// its line for listings, its factory and its keys (its options structs' field tables), from
// which configs/README.md's feature tables are generated.
//
// Adding a built-in feature:
//   1. features/my_feature.{h,cc}: the FeatureMap, an options struct with its field table
//      (util/option_fields.h) and `CreateMyFeature(const ParamBlock&, const FeatureSetup&)`,
//      which reads the block with ReadFields (config/read_fields.h); add the .cc to
//      features/CMakeLists.txt.
//   2. Its row in BuiltinFeatureTable() (features/builtin.cc).
//   3. `attend options-doc --write configs/README.md` adds its keys to the documentation.
#pragma once

#include <memory>
#include <vector>

#include "features/feature_map.h"
#include "util/option_fields.h"

namespace attend {

struct BuiltinFeature {
  const char* name;
  const char* summary;
  std::unique_ptr<FeatureMap> (*create)(const ParamBlock& params, const FeatureSetup& setup);
  // The keys of its entry besides name, weight, enabled and normalisation, with their
  // defaults; none for a feature without parameters.
  std::vector<FieldDescription> (*keys)();
};

// Every built-in feature, in the order of the documentation.
const std::vector<BuiltinFeature>& BuiltinFeatureTable();

// A registry holding every built-in feature.
FeatureRegistry BuiltinFeatures();

}  // namespace attend
