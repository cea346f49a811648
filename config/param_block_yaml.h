// Access to the YAML node behind a ParamBlock, for the few places that bind or emit YAML
// themselves (the options binding in pipeline/). Modules never include this.
#pragma once

#include <yaml-cpp/yaml.h>

#include "config/param_block.h"

namespace attend {

YAML::Node NodeOf(const ParamBlock& block);

}  // namespace attend
