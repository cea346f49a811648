// The run folder of SPEC 3.3. Records are appended and flushed frame by frame, so a run that
// stops early (Ctrl-C, a bad frame) keeps every frame it finished.
#pragma once

#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>

#include "pipeline/frame_record.h"

namespace cv {
class VideoWriter;
}

namespace attend {

class RunFolder {
 public:
  // Creates `dir` (and its parents) or takes it when empty. A non-empty folder is a
  // ConfigError unless `overwrite`, which removes only the files and folders a run writes.
  RunFolder(const std::string& dir, bool overwrite);
  ~RunFolder();
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;

  const std::string& dir() const { return dir_; }

  void WriteConfig(const std::string& yaml);
  void AppendFrame(const FrameRecord& record);
  // RUN/<kind>/NNNNNN.png
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
  std::ofstream frames_;
  std::unique_ptr<cv::VideoWriter> video_;
  std::string video_path_;
};

}  // namespace attend
