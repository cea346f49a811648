// Fields of the line-based text files read in io/ (gt/objects.csv, tracks.csv, OTB boxes).
// Errors are InputError naming the file, the line and the field.
#pragma once

#include <map>
#include <string>
#include <utility>

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

// The line of each (frame, id) row of a file: a second row of one target or object in one
// frame, which a scorer would count twice, is "PATH:LINE: WHAT ID again in frame FRAME (line L
// has it too)". A frame of more than kMaxTargetsPerRecord rows is "PATH:LINE: more than N
// WHATs in frame FRAME": scorers pair every row of a frame with every other of the other file.
class RowsOnce {
 public:
  void Add(int frame, int id, const std::string& path, int line, const char* what);

 private:
  std::map<std::pair<int, int>, int> lines_;
  std::map<int, int> per_frame_;
};

}  // namespace attend
