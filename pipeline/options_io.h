// The one place where YAML meets the options structs: each section of the configuration binds
// the field tables of its structs here, for reading, for writing the effective configuration
// and for listing and describing the keys (the documentation test checks configs/README.md
// against that list).
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

// Every key the configuration knows, as dotted paths ("sequence.width"), except the
// per-plugin keys inside `features`, in file order.
std::vector<std::string> ConfigurationKeys();

// The same keys with their type, range, default and a line of doc, from the options structs'
// field tables (util/option_fields.h): what `attend run --list-keys` prints.
std::vector<FieldDescription> DescribeConfiguration();

}  // namespace attend
