// Options that a plugin declares at run time, with no options struct to hold a field table
// (a Python feature's `options` dict of defaults, docs/PYTHON.md): each key with its default,
// whose type is the option's. Read here, like every other table, so a wrong type names the key
// and its line.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include "config/param_block.h"
#include "util/option_fields.h"

namespace attend {

using DeclaredValue = std::variant<bool, int, double, std::string, std::vector<std::string>,
                                   std::vector<double>>;

struct DeclaredOption {
  std::string key;
  DeclaredValue value;  // the default, replaced by the value read
};

// Reads each declared option present in `block` over its default, by the default's type.
// Keys not declared are left for the caller's CheckNoUnknownKeys().
void ReadDeclaredOptions(const ParamBlock& block, std::vector<DeclaredOption>* options);

// The options as help lines (util/option_fields.h), the defaults being their values.
std::vector<FieldDescription> DescribeDeclaredOptions(const std::vector<DeclaredOption>& options);

}  // namespace attend
