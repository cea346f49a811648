#include "pipeline/run_folder.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>

#include "io/ground_truth.h"
#include "io/image_file.h"
#include "io/pfm.h"
#include "util/error.h"
#include "util/opencv_extra.h"
#include "util/output_folder.h"
#include "util/json_text.h"

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
  lock_ = PrepareOutputFolder(dir_, overwrite, rules);
  const std::string frames_path = (fs::path(dir_) / "frames.jsonl").string();
  frames_.open(frames_path);
  if (!frames_) throw OutputError(frames_path + ": cannot write");
}

// A frame whose record was never written (a later dump of it failed, the disk filled, the run
// stopped on an error) leaves its finished dumps as temporaries: they are removed, so that no
// NNNNNN.part.* file is left beside the finished ones.
RunFolder::~RunFolder() {
  for (const auto& [temporary, path] : pending_) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
  }
}

void RunFolder::WriteConfig(const std::string& yaml) {
  const std::string path = (fs::path(dir_) / "config.yaml").string();
  std::ofstream out(path);
  out << yaml;
  if (!out) throw OutputError(path + ": cannot write");
}

namespace {

// "<path>: <what>: <the system's reason>", naming a full disk as such.
std::string WriteFailure(const std::string& path, const std::string& what, int error_number) {
  std::string message = path + ": " + what;
  if (error_number != 0) message += ": " + std::string(std::strerror(error_number));
  if (error_number == ENOSPC) message += " (the disk is full)";
  return message;
}

}  // namespace

void RunFolder::AppendFrame(const FrameRecord& record) {
  errno = 0;
  const std::string line = FrameRecordToJson(record) + "\n";
  frames_.write(line.data(), static_cast<std::streamsize>(line.size()));
  frames_.flush();
  if (!frames_) {
    // Part of the line may have reached the file: cut it back to the records before it, so
    // that every line of frames.jsonl stays a whole record.
    const int error_number = errno;
    frames_.close();
    const std::string path = dir_ + "/frames.jsonl";
    std::error_code ignored;
    fs::resize_file(path, frames_bytes_, ignored);
    throw OutputError(WriteFailure(path, "write failed", error_number));
  }
  frames_bytes_ += line.size();
  for (const auto& [temporary, path] : pending_) {
    std::error_code error;
    fs::rename(temporary, path, error);
    if (error) throw OutputError(path + ": cannot name the file: " + error.message());
  }
  pending_.clear();
}

void RunFolder::WritePending(const std::string& path,
                             const std::function<bool(const std::string&)>& write) {
  const fs::path target(path);
  // The extension stays last: imwrite chooses the format by it.
  const std::string temporary =
      (target.parent_path() / (target.stem().string() + ".part" + target.extension().string()))
          .string();
  errno = 0;
  bool written = false;
  try {
    written = write(temporary);
  } catch (const OutputError& e) {
    // Named by the file's own name, not the temporary one.
    std::error_code ignored;
    fs::remove(temporary, ignored);
    std::string message = e.what();
    const size_t at = message.find(temporary);
    if (at != std::string::npos) message.replace(at, temporary.size(), path);
    throw OutputError(message);
  } catch (...) {
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw;
  }
  if (!written) {
    const int error_number = errno;
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw OutputError(WriteFailure(path, "cannot write", error_number));
  }
  pending_.emplace_back(temporary, path);
}

void RunFolder::WriteImage(const std::string& kind, int frame, const cv::Mat& image) {
  const fs::path folder = fs::path(dir_) / kind;
  std::error_code error;
  fs::create_directories(folder, error);
  const std::string path = (folder / (FrameStem(frame) + ".png")).string();
  if (error) throw OutputError(folder.string() + ": cannot create the folder: " + error.message());
  WritePending(path, [&](const std::string& file) { return attend::WriteImage(file, image); });
}

void RunFolder::WriteMap(const std::string& kind, int frame, const cv::Mat& map,
                         const cv::Mat& preview, bool pfm, bool png) {
  const fs::path folder = fs::path(dir_) / kind;
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw OutputError(folder.string() + ": cannot create the folder");
  if (pfm) {
    WritePending((folder / (FrameStem(frame) + ".pfm")).string(), [&](const std::string& file) {
      WritePfm(file, map);  // throws OutputError itself
      return true;
    });
  }
  if (png) {
    cv::Mat image;
    preview.convertTo(image, CV_8U, 255.0);
    WritePending((folder / (FrameStem(frame) + ".png")).string(),
                 [&](const std::string& file) { return attend::WriteImage(file, image); });
  }
}

void RunFolder::AppendVideoFrame(const std::string& name, const cv::Mat& image, double fps) {
  if (!video_) {
    video_path_ = (fs::path(dir_) / (name + ".avi")).string();
    // The encoder takes frame rates in about this range: below 0.01 frames a second it has no
    // time base, and at 1e-9 FFmpeg padded five frames into a 44 GB file before it was stopped
    // (issue 30). A time-lapse or a high-speed sequence is played back at the nearest rate in
    // range, with a note.
    constexpr double kSlowest = 1.0, kFastest = 1000.0;
    const double rate = std::clamp(fps, kSlowest, kFastest);
    if (rate != fps) {
      std::cerr << "attend: note: " << video_path_ << " plays at " << rate
                << " frames a second: the sequence's " << fps
                << " is outside what the video is written at (" << kSlowest << " to " << kFastest
                << ")\n";
    }
    video_ = cvextra::Get("output.video").OpenWriter(
        video_path_, cvextra::FourCc('M', 'J', 'P', 'G'), rate, image.size());
    if (!video_->IsOpened()) {
      throw OutputError(video_path_ + ": this OpenCV build cannot write Motion-JPEG video " +
                        "(set output.video: false)");
    }
  }
  video_->Write(image);
}

void RunFolder::WriteSummary(const nlohmann::ordered_json& summary) {
  WriteJson("summary.json", summary);
}

void RunFolder::WriteJson(const std::string& name, const nlohmann::ordered_json& value) {
  const nlohmann::ordered_json& summary = value;
  const fs::path path = fs::path(dir_) / name;
  const fs::path temporary = fs::path(dir_) / (name + ".tmp");
  errno = 0;
  std::ofstream out(temporary);
  out << JsonText(summary, 2) << "\n";
  out.close();
  if (!out) {
    // No half-written file is left behind under either name.
    const int error_number = errno;
    std::error_code ignored;
    fs::remove(temporary, ignored);
    throw OutputError(WriteFailure(path.string(), "cannot write", error_number));
  }
  std::error_code error;
  fs::rename(temporary, path, error);
  if (error) throw OutputError(path.string() + ": cannot write: " + error.message());
}

}  // namespace attend
