// Fields of the line-based text files read in io/ (gt/objects.csv, tracks.csv, OTB boxes).
// Errors are InputError naming the file, the line and the field.
#pragma once

#include <string>

namespace attend {

// `text` without spaces, tabs and carriage returns at either end.
std::string TrimField(const std::string& text);

// `text` as a finite number (with `allow_nan`, also "nan"); "PATH:LINE: field 'FIELD' is not a
// number: 'TEXT'" otherwise.
double ParseNumberField(const std::string& text, const std::string& path, int line,
                        const char* field, bool allow_nan = false);

// `text` as a whole number, still a double so that the caller checks its range before
// converting; "PATH:LINE: field 'FIELD' is not an integer: 'TEXT'" otherwise.
double ParseWholeField(const std::string& text, const std::string& path, int line,
                       const char* field);

}  // namespace attend
