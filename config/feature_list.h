// The `features:` list of the configuration (SPEC 3.4): each entry names a feature plugin,
// gives its weight in the saliency sum, and carries the plugin's own parameters. The list is
// parsed here; each plugin reads its own block through the ParamBlock and then calls
// CheckNoUnknownKeys(), so a mistyped plugin parameter is an error too.
#pragma once

#include <string>
#include <vector>

#include "config/param_block.h"

namespace attend {

struct FeatureSpec {
  std::string name;     // plugin name, unique within the list
  double weight = 1.0;  // weight in the saliency sum, >= 0
  // A disabled feature is still created (so its parameters are checked) but never computed:
  // it leaves no map, no dump and no time.
  bool enabled = true;
  // The normalisation of this feature's map before the sum: a name in the feature registry's
  // normalisations (minmax, local_maxima, or one a plugin added); "" is saliency.normalisation.
  std::string normalisation;
  // With `saliency.combination: product`: this map is added to the weighted geometric mean of
  // the other maps instead of being a factor in it (MultiplyMaps). A channel that is 0 on most
  // images (faces) then leaves those images' maps as they are instead of flattening them. No
  // effect in `sum`.
  bool additive = false;
  // The whole entry; `name`, `weight`, `enabled`, `normalisation` and `additive` are already marked
  // as read, so
  // a plugin reads its own keys and then calls params.CheckNoUnknownKeys().
  ParamBlock params;
};

// Reads root[key] as a list of {name, weight, ...} maps. Missing name, negative weight,
// duplicate names or an entry that is not a map: ConfigError naming the line.
std::vector<FeatureSpec> ReadFeatureList(const ParamBlock& root, const std::string& key);

}  // namespace attend
