// A plugin that registers a name a built-in feature already has: attend must refuse it.
#include "features/plugin_api.h"

namespace {
void Register(attend::FeatureRegistry* registry) {
  registry->Add("skin", "a second skin",
                [](const attend::ParamBlock&, const attend::FeatureSetup&) {
                  return std::unique_ptr<attend::FeatureMap>();
                });
}
}  // namespace

ATTEND_PLUGIN("name_clash", Register)
