// The one place where YAML meets the options structs: every configuration key is bound to
// its field here, for reading, for writing the effective configuration and for listing the
// keys (the documentation test checks configs/README.md against that list).
#pragma once

#include <string>
#include <vector>

#include "config/param_block.h"
#include "pipeline/attend_options.h"

namespace attend {

// Starts from the defaults and overlays the keys present in `root`. Unknown keys, wrong
// types and values out of range: ConfigError naming the key and line (or the --set).
AttendOptions ReadOptions(const ParamBlock& root);

// Reads a configuration file and applies "key.path=value" overrides in order.
AttendOptions LoadOptions(const std::string& path, const std::vector<std::string>& overrides);

// The effective configuration as YAML: every key, defaults included. Reading it back gives
// the same options.
std::string OptionsToYaml(const AttendOptions& options);

// Every scalar or list key the configuration knows, as dotted paths ("sequence.width"),
// except the per-plugin keys inside `features`.
std::vector<std::string> ConfigurationKeys();

}  // namespace attend
