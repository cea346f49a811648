#include "config/feature_list.h"

#include <set>

namespace attend {

std::vector<FeatureSpec> ReadFeatureList(const ParamBlock& root, const std::string& key) {
  std::vector<FeatureSpec> specs;
  std::set<std::string> names;
  for (const ParamBlock& entry : root.Children(key)) {
    FeatureSpec spec;
    spec.name = entry.RequireString("name");
    if (spec.name.empty()) entry.Fail("name", "must not be empty");
    spec.weight = entry.GetDouble("weight", 1.0, Range::AtLeast(0.0));
    spec.enabled = entry.GetBool("enabled", true);
    spec.normalisation = entry.GetString("normalisation", "");
    spec.additive = entry.GetBool("additive", false);
    if (!names.insert(spec.name).second) {
      entry.Fail("name", "feature '" + spec.name + "' is listed twice");
    }
    spec.params = entry;
    specs.push_back(std::move(spec));
  }
  return specs;
}

}  // namespace attend
