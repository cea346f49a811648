#include "pipeline/run_folder.h"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "io/ground_truth.h"
#include "io/pfm.h"
#include "util/error.h"
#include "util/output_folder.h"

namespace fs = std::filesystem;

namespace attend {

const std::vector<std::string>& RunFolder::OwnEntries() {
  static const std::vector<std::string> entries = {
      "config.yaml", "frames.jsonl", "summary.json", "overlay.avi", "saliency",
      "inhibition",  "inhibited",    "features",     "overlay",     "regions",
      "scanpath.json"};
  return entries;
}

RunFolder::RunFolder(const std::string& dir, bool overwrite) : dir_(dir) {
  OutputFolderRules rules;
  rules.what = "run";
  rules.own_entries = OwnEntries();
  rules.is_previous_output = [](const std::string& folder) {
    return fs::exists(fs::path(folder) / "frames.jsonl") ||
           fs::exists(fs::path(folder) / "summary.json");
  };
  PrepareOutputFolder(dir_, overwrite, rules);
  const std::string frames_path = (fs::path(dir_) / "frames.jsonl").string();
  frames_.open(frames_path);
  if (!frames_) throw OutputError(frames_path + ": cannot write");
}

RunFolder::~RunFolder() = default;

void RunFolder::WriteConfig(const std::string& yaml) {
  const std::string path = (fs::path(dir_) / "config.yaml").string();
  std::ofstream out(path);
  out << yaml;
  if (!out) throw OutputError(path + ": cannot write");
}

void RunFolder::AppendFrame(const FrameRecord& record) {
  frames_ << FrameRecordToJson(record) << "\n";
  frames_.flush();
  if (!frames_) throw OutputError(dir_ + "/frames.jsonl: write failed (disk full?)");
}

void RunFolder::WriteImage(const std::string& kind, int frame, const cv::Mat& image) {
  const fs::path folder = fs::path(dir_) / kind;
  std::error_code error;
  fs::create_directories(folder, error);
  const std::string path = (folder / (FrameStem(frame) + ".png")).string();
  if (error || !cv::imwrite(path, image)) throw OutputError(path + ": cannot write the image");
}

void RunFolder::WriteMap(const std::string& kind, int frame, const cv::Mat& map,
                         const cv::Mat& preview, bool pfm, bool png) {
  const fs::path folder = fs::path(dir_) / kind;
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw OutputError(folder.string() + ": cannot create the folder");
  if (pfm) WritePfm((folder / (FrameStem(frame) + ".pfm")).string(), map);
  if (png) {
    cv::Mat image;
    preview.convertTo(image, CV_8U, 255.0);
    const std::string path = (folder / (FrameStem(frame) + ".png")).string();
    if (!cv::imwrite(path, image)) throw OutputError(path + ": cannot write the image");
  }
}

void RunFolder::AppendVideoFrame(const std::string& name, const cv::Mat& image, double fps) {
  if (!video_) {
    video_path_ = (fs::path(dir_) / (name + ".avi")).string();
    video_ = std::make_unique<cv::VideoWriter>(
        video_path_, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps, image.size());
    if (!video_->isOpened()) {
      throw OutputError(video_path_ + ": this OpenCV build cannot write Motion-JPEG video " +
                        "(set output.video: false)");
    }
  }
  video_->write(image);
}

void RunFolder::WriteSummary(const nlohmann::ordered_json& summary) {
  WriteJson("summary.json", summary);
}

void RunFolder::WriteJson(const std::string& name, const nlohmann::ordered_json& value) {
  const nlohmann::ordered_json& summary = value;
  const fs::path path = fs::path(dir_) / name;
  const fs::path temporary = fs::path(dir_) / (name + ".tmp");
  {
    std::ofstream out(temporary);
    out << summary.dump(2) << "\n";
    if (!out) throw OutputError(temporary.string() + ": cannot write");
  }
  fs::rename(temporary, path);
}

}  // namespace attend
