// A plugin library built for another plugin ABI version: attend must refuse it.
#include "features/plugin_api.h"

namespace {
void Register(attend::FeatureRegistry*) {}
}  // namespace

extern "C" __attribute__((visibility("default"))) const AttendPluginInfo* attend_plugin() {
  static const AttendPluginInfo info{ATTEND_PLUGIN_ABI_VERSION + 98, "abi_mismatch", &Register};
  return &info;
}
