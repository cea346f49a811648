// The option tables of configs/README.md, generated from the field tables
// (util/option_fields.h): key, type, default, range and the field's doc in one row. The prose
// around them is written by hand; each table sits between two marker lines,
//
//   <!-- options: SECTION -->
//   ...the generated table...
//   <!-- end options -->
//
// SECTION being a configuration section (sequence, live, ..., tracker, or the top-level keys
// plugins and threads) or `features` (every built-in feature with its keys).
// `attend options-doc --write configs/README.md` regenerates them; a test fails when the file
// differs from what the tables give.
#pragma once

#include <string>
#include <vector>

#include "util/option_fields.h"

namespace attend {

// The built-in features' own keys, as `features.NAME.KEY` (features/builtin.h).
std::vector<FieldDescription> DescribeFeatureKeys();

// Every key `--set` takes: the configuration's (DescribeConfiguration) and the built-in
// features'; what `attend run --list-keys` prints.
std::vector<FieldDescription> DescribeEveryKey();

// The markdown table of one section (see above). An unknown section: ConfigError.
std::string OptionTable(const std::string& section);

// `text` (configs/README.md) with the table between each pair of markers replaced by the
// generated one. A marker without its end, or of an unknown section: ConfigError naming the
// line.
std::string WithGeneratedTables(const std::string& text);

// Rewrites the tables of the file at `path` in place; false when they were up to date (the
// file is then left alone). A file that cannot be read or written: ConfigError.
bool WriteGeneratedTables(const std::string& path);

}  // namespace attend
