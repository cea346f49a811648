// A plugin library built for another plugin ABI version: attend must refuse it.
#include "features/plugin_api.h"

namespace {
void Register(attend::FeatureRegistry*) {}
}  // namespace

extern "C" __attribute__((visibility("default"))) const AttendPluginInfo* attend_plugin() {
  // Version 99: one no attend has (the CLI test expects the number in the message).
  static_assert(ATTEND_PLUGIN_ABI_VERSION != 99);
  static const AttendPluginInfo info{99, "abi_mismatch", &Register};
  return &info;
}
