// Preparing the folder a command writes into, without ever deleting what it did not write.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "util/folder_lock.h"

namespace attend {

struct OutputFolderRules {
  std::string what;                     // "run", "sequence": for messages
  std::vector<std::string> own_entries; // files and folders the command writes below it
  // True when the folder holds an earlier output of the same command, the only kind that
  // `overwrite` may replace.
  std::function<bool(const std::string& folder)> is_previous_output;
  // Lock the folder for the writer (util/folder_lock.h): a second writer is refused while the
  // returned lock lives. Off for outputs written in one go by a helper that holds its own.
  bool lock = true;
};

// Creates `folder` (and its parents) or takes it when empty. A non-empty folder is an
// OutputError unless `overwrite` and it holds a previous output, in which case only
// `own_entries` are removed; other files stay. An empty path is an OutputError. With
// `rules.lock`, the folder is locked first (a folder in use by another writer is an
// OutputError naming it) and the lock is returned: keep it until the output is written.
[[nodiscard]] FolderLock PrepareOutputFolder(const std::string& folder, bool overwrite, const OutputFolderRules& rules);

// Writes a file so that `path` holds either its old content or the whole new one: `write`
// fills a temporary file beside it (.NAME.tmp-PID), returning false or throwing an attend
// Error when it cannot, and the temporary is then renamed over `path`. On failure the
// temporary is removed and OutputError "PATH: cannot write WHAT" is thrown, with the reason
// in parentheses when there is one. The folder must exist.
void ReplaceFile(const std::string& path, const std::string& what,
                 const std::function<bool(const std::string& temporary)>& write);

// ReplaceFile with `text` as the new content; a failure names the system's reason ("the disk
// is full: No space left on device").
void ReplaceFileText(const std::string& path, const std::string& text, const std::string& what = "");

// The whole content of a file, "" when it cannot be read.
std::string ReadFileText(const std::string& path);

}  // namespace attend
