// A configuration as flat "key.path" -> value text, for comparing two of them (attend compare):
// maps nest with dots, lists of maps with unique `name`s by name (features.skin.weight), other
// lists of maps by index, lists of scalars and scalars as their YAML text.
#pragma once

#include <map>
#include <string>

#include "config/param_block.h"

namespace attend {

// Every value of `block`, flattened; an empty map is "{}". Reads the tree only: no key is
// marked as known.
std::map<std::string, std::string> FlattenedValues(const ParamBlock& block);

}  // namespace attend
