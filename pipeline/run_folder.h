// The run folder of SPEC 3.3. Records are appended and flushed frame by frame, so a run that
// stops early (Ctrl-C, a bad frame) keeps every frame it finished.
#pragma once

#include <cstdint>
#include <fstream>
#include <functional>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

#include "io/frame_record.h"
#include "util/folder_lock.h"

namespace attend::cvextra {
class Writer;
}  // namespace attend::cvextra

namespace attend {

class RunFolder {
 public:
  // Creates `dir` (and its parents) or takes it when empty, and locks it while the run lives
  // (a folder in use by another run is an OutputError). A non-empty folder is an OutputError
  // unless `overwrite`, which removes only the files and folders a run writes.
  RunFolder(const std::string& dir, bool overwrite);
  ~RunFolder();
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;

  const std::string& dir() const { return dir_; }

  void WriteConfig(const std::string& yaml);
  // Appends the record and flushes it; then the frame's images and maps written since the
  // last record (WriteImage, WriteMap) get their names. A run stopped in between (SIGKILL)
  // leaves no image or map under a frame's name without that frame's record.
  void AppendFrame(const FrameRecord& record);
  // RUN/<kind>/NNNNNN.png (named by the next AppendFrame)
  void WriteImage(const std::string& kind, int frame, const cv::Mat& image);
  // RUN/<kind>/NNNNNN.pfm (the map itself, `pfm`) and RUN/<kind>/NNNNNN.png (an 8-bit preview:
  // `preview`, a map in [0, 1], times 255, with `png`). `kind` may hold a slash
  // ("features/skin").
  void WriteMap(const std::string& kind, int frame, const cv::Mat& map, const cv::Mat& preview,
                bool pfm, bool png);
  // Appends a frame to RUN/<name>.avi (Motion-JPEG), opened on first use.
  void AppendVideoFrame(const std::string& name, const cv::Mat& image, double fps);
  // Written to a temporary file and renamed, so summary.json is never half-written.
  void WriteSummary(const nlohmann::ordered_json& summary);
  // DIR/<name> (a JSON file of the run's own, such as scanpath.json), written whole by a rename.
  void WriteJson(const std::string& name, const nlohmann::ordered_json& value);

  // The entries a run writes below its folder (what --overwrite removes).
  static const std::vector<std::string>& OwnEntries();

 private:
  std::string dir_;
  FolderLock lock_;  // held while the run writes (a second writer is refused)
  std::ofstream frames_;
  uintmax_t frames_bytes_ = 0;  // the size of frames.jsonl up to its last whole record
  std::unique_ptr<cvextra::Writer> video_;
  std::string video_path_;
  // Files written under a temporary name, with the names they take at the next AppendFrame.
  std::vector<std::pair<std::string, std::string>> pending_;
  // Writes through `write` to a temporary name in the folder of `path`, renamed by the next
  // AppendFrame.
  void WritePending(const std::string& path, const std::function<bool(const std::string&)>& write);
};

}  // namespace attend
