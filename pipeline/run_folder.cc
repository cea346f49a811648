#include "pipeline/run_folder.h"

#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/videoio.hpp>

#include "io/ground_truth.h"
#include "util/error.h"

namespace fs = std::filesystem;

namespace attend {

const std::vector<std::string>& RunFolder::OwnEntries() {
  static const std::vector<std::string> entries = {"config.yaml", "frames.jsonl", "summary.json",
                                                   "overlay.avi", "saliency",     "inhibition",
                                                   "inhibited",   "features",     "overlay"};
  return entries;
}

RunFolder::RunFolder(const std::string& dir, bool overwrite) : dir_(dir) {
  std::error_code error;
  if (fs::exists(dir_, error)) {
    if (!fs::is_directory(dir_, error)) {
      throw ConfigError(dir_ + ": the output path exists and is not a folder");
    }
    if (!fs::is_empty(dir_, error)) {
      if (!overwrite) {
        throw ConfigError(dir_ + ": the output folder is not empty (use --overwrite to replace " +
                          "a previous run there)");
      }
      for (const std::string& entry : OwnEntries()) fs::remove_all(fs::path(dir_) / entry, error);
    }
  }
  fs::create_directories(dir_, error);
  if (error) throw ConfigError(dir_ + ": cannot create the output folder: " + error.message());
  const std::string frames_path = (fs::path(dir_) / "frames.jsonl").string();
  frames_.open(frames_path);
  if (!frames_) throw ConfigError(frames_path + ": cannot write");
}

RunFolder::~RunFolder() = default;

void RunFolder::WriteConfig(const std::string& yaml) {
  const std::string path = (fs::path(dir_) / "config.yaml").string();
  std::ofstream out(path);
  out << yaml;
  if (!out) throw ConfigError(path + ": cannot write");
}

void RunFolder::AppendFrame(const FrameRecord& record) {
  frames_ << FrameRecordToJson(record) << "\n";
  frames_.flush();
  if (!frames_) throw InputError(dir_ + "/frames.jsonl: write failed (disk full?)");
}

void RunFolder::WriteImage(const std::string& kind, int frame, const cv::Mat& image) {
  const fs::path folder = fs::path(dir_) / kind;
  std::error_code error;
  fs::create_directories(folder, error);
  const std::string path = (folder / (FrameStem(frame) + ".png")).string();
  if (error || !cv::imwrite(path, image)) throw InputError(path + ": cannot write the image");
}

void RunFolder::AppendVideoFrame(const std::string& name, const cv::Mat& image, double fps) {
  if (!video_) {
    video_path_ = (fs::path(dir_) / (name + ".avi")).string();
    video_ = std::make_unique<cv::VideoWriter>(
        video_path_, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps, image.size());
    if (!video_->isOpened()) {
      throw ConfigError(video_path_ + ": this OpenCV build cannot write Motion-JPEG video " +
                        "(set output.video: false)");
    }
  }
  video_->write(image);
}

void RunFolder::WriteSummary(const nlohmann::ordered_json& summary) {
  const fs::path path = fs::path(dir_) / "summary.json";
  const fs::path temporary = fs::path(dir_) / "summary.json.tmp";
  {
    std::ofstream out(temporary);
    out << summary.dump(2) << "\n";
    if (!out) throw InputError(temporary.string() + ": cannot write");
  }
  fs::rename(temporary, path);
}

}  // namespace attend
