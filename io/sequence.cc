#include "io/sequence.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>  // the CAP_ constants only
#include <optional>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "config/param_block.h"
#include "io/image_file.h"
#include "io/live_source.h"
#include "util/error.h"
#include "util/opencv_extra.h"
#include "util/strings.h"

namespace attend {

namespace fs = std::filesystem;

namespace {

std::string SizeText(cv::Size size) {
  return std::to_string(size.width) + "x" + std::to_string(size.height);
}

std::string FrameWhere(int index, const std::string& path) {
  return "frame " + std::to_string(index) + " (" + path + ")";
}

// One frame at the size it has in the source.
struct NativeFrame {
  cv::Mat left;
  cv::Mat right;  // empty when monocular
  std::string left_path;
  std::string right_path;
};

// Reads the frames of one kind of source at their native size. Open-time facts (stereo, name,
// fps, calibration, folder) go into `info` when the reader is made.
class NativeReader {
 public:
  virtual ~NativeReader() = default;
  // Frames in the source, or -1 when it cannot tell.
  virtual int Count() const = 0;
  // Reads frame `index` of the source; successive calls ask for increasing indices. False when
  // the source has no such frame; InputError when the frame exists but cannot be used.
  virtual bool Read(int index, NativeFrame* frame) = 0;
};

// ---------------------------------------------------------------------------------------------
// Folders: SEQ/left/*, SEQ/right/*, SEQ/sequence.yaml.

// The last non-empty component of a path ("data/seq/" -> "seq").
std::string FolderStem(const std::string& folder) {
  fs::path path = fs::absolute(fs::path(folder)).lexically_normal();
  if (path.filename().empty()) path = path.parent_path();
  return path.filename().string();
}

// Asking for a key records it as known even when the value is not a scalar, so this accepts
// any value; the keys it is used for are notes for people, never read by attend.
void AcceptAnyValue(const ParamBlock& block, const std::string& key) {
  try {
    block.GetString(key, "");
  } catch (const ConfigError&) {
  }
}

// SEQ/sequence.yaml describes the data, so any problem in it is bad input (exit status 3),
// reported with the file and line that ParamBlock gives.
void ReadSequenceYaml(const std::string& path, SequenceInfo* info) {
  try {
    const ParamBlock block = ParamBlock::LoadFile(path);
    info->name = block.GetString("name", info->name);
    if (info->name.empty()) block.Fail("name", "must not be empty");
    info->fps = block.GetDouble("fps", info->fps, Range::Above(0));
    info->focal_px = block.GetDouble("focal_px", 0.0, Range::AtLeast(0));
    info->baseline_m = block.GetDouble("baseline_m", 0.0, Range::AtLeast(0));
    AcceptAnyValue(block, "generator");
    AcceptAnyValue(block, "frames");
    block.CheckNoUnknownKeys();
  } catch (const ConfigError& e) {
    throw InputError(e.what());
  }
}

// Where left/ and right/ name their frames alike (they share at least one file name, less its
// extension), every name must be in both: a name in one folder only would pair every later
// frame with the wrong partner. Returns what is wrong, or "" (also when no name is shared:
// folders named differently, left_0001 and right_0001, pair by position).
std::string UnmatchedFrameName(const std::vector<std::string>& left,
                               const std::vector<std::string>& right) {
  auto stems = [](const std::vector<std::string>& files) {
    std::vector<std::string> names;
    for (const std::string& file : files) names.push_back(fs::path(file).stem().string());
    return names;
  };
  const std::vector<std::string> left_names = stems(left), right_names = stems(right);
  const std::set<std::string> left_set(left_names.begin(), left_names.end());
  const std::set<std::string> right_set(right_names.begin(), right_names.end());
  const bool shared = std::any_of(left_names.begin(), left_names.end(),
                                  [&](const std::string& n) { return right_set.count(n) > 0; });
  if (!shared) return "";
  for (size_t i = 0; i < left.size(); ++i) {
    if (right_set.count(left_names[i]) == 0) {
      return left[i] + " has no partner named " + left_names[i] + ".* in right/";
    }
  }
  for (size_t i = 0; i < right.size(); ++i) {
    if (left_set.count(right_names[i]) == 0) {
      return right[i] + " has no partner named " + right_names[i] + ".* in left/";
    }
  }
  return "";
}

class FolderReader final : public NativeReader {
 public:
  FolderReader(const SequenceOptions& options, SequenceInfo* info) {
    const fs::path folder(options.folder);
    const std::string what = options.Describe();
    std::error_code error;
    if (!fs::exists(folder, error)) throw InputError(what + ": no such folder");
    if (!fs::is_directory(folder, error)) throw InputError(what + ": not a folder");
    const fs::path left = folder / "left";
    const fs::path right = folder / "right";
    if (!fs::is_directory(left, error)) {
      throw InputError(what + ": no left/ folder (expected " + left.string() + "/000000.png ...)");
    }
    info->stereo = fs::is_directory(right, error);
    left_files_ = ListFrameFiles(left.string(), what);
    if (info->stereo) right_files_ = ListFrameFiles(right.string(), what);
    if (left_files_.empty()) {
      throw InputError(what + ": no frames in " + left.string() + " (expected files ending in " +
                       Join(FrameFileExtensions(), ", ") + ")");
    }
    if (info->stereo) {
      const std::string unmatched = UnmatchedFrameName(left_files_, right_files_);
      if (right_files_.size() != left_files_.size()) {
        throw InputError(what + ": left/ has " + std::to_string(left_files_.size()) +
                         " frames but right/ has " + std::to_string(right_files_.size()) +
                         (unmatched.empty() ? "" : "; " + unmatched));
      }
      if (!unmatched.empty()) {
        throw InputError(what + ": " + unmatched +
                         " (left/ and right/ name their frames alike, so a frame pairs with the "
                         "file of its name)");
      }
    }
    info->name = FolderStem(options.folder);
    info->folder = options.folder;
    const fs::path yaml = folder / "sequence.yaml";
    if (fs::exists(yaml, error)) ReadSequenceYaml(yaml.string(), info);
  }

  int Count() const override { return static_cast<int>(left_files_.size()); }

  bool Read(int index, NativeFrame* frame) override {
    if (index < 0 || index >= Count()) return false;
    frame->left_path = left_files_[index];
    frame->left = ReadFrameFile(index, frame->left_path);
    if (!right_files_.empty()) {
      frame->right_path = right_files_[index];
      frame->right = ReadFrameFile(index, frame->right_path);
    }
    return true;
  }

 private:
  std::vector<std::string> left_files_;
  std::vector<std::string> right_files_;
};

// A plain folder of frames, monocular: DIR/* (for example an OTB sequence's img/). There is no
// sequence.yaml and no gt/ below it.
class ImageFolderReader final : public NativeReader {
 public:
  ImageFolderReader(const SequenceOptions& options, SequenceInfo* info) {
    const std::string what = options.Describe();
    files_ = ListFrameFiles(options.images, what);
    if (files_.empty()) {
      throw InputError(what + ": no frames (expected files ending in " +
                       Join(FrameFileExtensions(), ", ") + "); the folder holds no images");
    }
    info->stereo = false;
    info->name = FolderStem(options.images);
  }

  int Count() const override { return static_cast<int>(files_.size()); }

  bool Read(int index, NativeFrame* frame) override {
    if (index < 0 || index >= Count()) return false;
    frame->left_path = files_[index];
    frame->left = ReadFrameFile(index, frame->left_path);
    frame->right = cv::Mat();
    frame->right_path.clear();
    return true;
  }

 private:
  std::vector<std::string> files_;
};

// ---------------------------------------------------------------------------------------------
// Videos: a pair, one side-by-side, or one monocular.

class VideoReader final : public NativeReader {
 public:
  enum class Layout { kMono, kPair, kSideBySide };

  VideoReader(const SequenceOptions& options, SequenceInfo* info) {
    if (!options.video.empty()) {
      layout_ = Layout::kMono;
      paths_ = {options.video};
    } else if (!options.side_by_side_video.empty()) {
      layout_ = Layout::kSideBySide;
      paths_ = {options.side_by_side_video};
    } else {
      layout_ = Layout::kPair;
      paths_ = {options.left_video, options.right_video};
    }
    std::vector<int> counts;
    for (size_t i = 0; i < paths_.size(); ++i) {
      captures_.push_back(OpenCapture(paths_[i]));
      const double count = captures_[i]->Get(cv::CAP_PROP_FRAME_COUNT);
      counts.push_back(count > 0 && std::isfinite(count) ? static_cast<int>(count) : -1);
    }
    count_ = counts[0];
    if (layout_ == Layout::kPair) {
      if (counts[0] > 0 && counts[1] > 0 && counts[0] != counts[1]) {
        throw InputError(options.Describe() + ": the left video has " + std::to_string(counts[0]) +
                         " frames but the right video has " + std::to_string(counts[1]));
      }
      if (counts[0] < 0 || counts[1] < 0) count_ = -1;
    }
    info->stereo = layout_ != Layout::kMono;
    info->name = fs::path(paths_[0]).stem().string();
    const double fps = captures_[0]->Get(cv::CAP_PROP_FPS);
    if (fps > 0 && std::isfinite(fps)) info->fps = fps;
  }

  int Count() const override { return count_; }

  bool Read(int index, NativeFrame* frame) override {
    // Frames before `index` are grabbed but not decoded: that is how a stride or a first frame
    // skips through a stream that cannot seek exactly.
    while (position_ < index) {
      if (!Advance(/*decode=*/false, nullptr)) return false;
    }
    std::vector<cv::Mat> images;
    if (!Advance(/*decode=*/true, &images)) return false;
    const int read_index = position_ - 1;
    for (size_t i = 0; i < images.size(); ++i) {
      images[i] = VideoFrameToBgr(images[i], read_index, FramePath(i, read_index));
    }
    frame->left_path = FramePath(0, read_index);
    if (layout_ == Layout::kMono) {
      frame->left = images[0];
      frame->right = cv::Mat();
      frame->right_path.clear();
    } else if (layout_ == Layout::kPair) {
      frame->left = images[0];
      frame->right = images[1];
      frame->right_path = FramePath(1, read_index);
    } else {
      const cv::Mat& both = images[0];
      if (both.cols % 2 != 0) {
        throw InputError(FrameWhere(read_index, frame->left_path) + ": width " +
                         std::to_string(both.cols) +
                         " is odd, so it cannot be split into equal left and right halves");
      }
      const int half = both.cols / 2;
      // Copies, so that each view is continuous and independent of the other.
      frame->left = both(cv::Rect(0, 0, half, both.rows)).clone();
      frame->right = both(cv::Rect(half, 0, half, both.rows)).clone();
      frame->right_path = frame->left_path;
    }
    return true;
  }

 private:
  static std::unique_ptr<cvextra::Capture> OpenCapture(const std::string& path) {
    // A missing file is reported before OpenCV tries every backend on it. Paths with '%' are
    // image-sequence patterns ("frames/%06d.png") that only the video backend can resolve.
    std::error_code error;
    if (path.find('%') == std::string::npos && !fs::exists(path, error)) {
      throw InputError("video " + path + ": no such file");
    }
    // OpenCV's videoio is in the optional module (util/opencv_extra.h).
    cvextra::Module& opencv = cvextra::Get("video " + path);
    std::unique_ptr<cvextra::Capture> capture;
    try {
      capture = opencv.OpenCapture(path, cv::CAP_ANY);
    } catch (const cv::Exception& e) {
      throw InputError("video " + path + ": cannot be opened: " + e.what());
    }
    if (capture == nullptr || !capture->IsOpened()) {
      throw InputError("video " + path + ": cannot be opened (not a video OpenCV can decode)");
    }
    return capture;
  }

  std::string FramePath(size_t view, int index) const {
    return paths_[view] + "#" + std::to_string(index);
  }

  // Moves every capture one frame on; false at the end of all of them. A pair whose videos end
  // at different frames is inconsistent input.
  bool Advance(bool decode, std::vector<cv::Mat>* images) {
    std::vector<bool> ok(captures_.size());
    for (size_t i = 0; i < captures_.size(); ++i) {
      if (decode) {
        // A fresh matrix per frame: frames handed out earlier must never share its buffer.
        cv::Mat image;
        ok[i] = captures_[i]->Read(&image) && !image.empty();
        images->push_back(image);
      } else {
        ok[i] = captures_[i]->Grab();
      }
    }
    const int index = position_;
    ++position_;
    if (ok.size() == 2 && ok[0] != ok[1]) {
      const size_t ended = ok[0] ? 1 : 0;
      throw InputError(FrameWhere(index, FramePath(ended, index)) + ": the " +
                       (ended == 0 ? "left" : "right") + " video ends here but the " +
                       (ended == 0 ? "right" : "left") + " video goes on");
    }
    return ok[0];
  }

  Layout layout_ = Layout::kMono;
  std::vector<std::string> paths_;
  std::vector<std::unique_ptr<cvextra::Capture>> captures_;
  int count_ = -1;
  int position_ = 0;  // index of the frame the next read or grab returns
};

// ---------------------------------------------------------------------------------------------
// Range, stride, size checks and the working size, common to every source.

class Sequence final : public FrameSource {
 public:
  Sequence(const SequenceOptions& options, std::unique_ptr<NativeReader> reader, SequenceInfo info)
      : reader_(std::move(reader)),
        info_(std::move(info)),
        stride_(options.stride),
        next_index_(options.first_frame),
        last_index_(options.last_frame),
        what_(options.Describe()) {
    const int count = reader_->Count();
    const std::string& what = what_;
    if (count >= 0 && options.first_frame >= count) {
      throw InputError(what + ": the frame range starts at frame " +
                       std::to_string(options.first_frame) + " but the source has " +
                       std::to_string(count) + " frames (0.." + std::to_string(count - 1) + ")");
    }
    if (count >= 0) {
      last_index_ = last_index_ < 0 ? count - 1 : std::min(last_index_, count - 1);
      info_.frame_count = (last_index_ - options.first_frame) / stride_ + 1;
    } else {
      info_.frame_count = -1;
    }

    // The first frame fixes the native size; it is kept and handed out by the first Next().
    NativeFrame first;
    if (!reader_->Read(options.first_frame, &first)) {
      throw InputError(what + ": there is no frame " + std::to_string(options.first_frame) +
                       " (the source is empty or the frame range starts beyond its end)");
    }
    SizeSequence(options, first.left.size(), &info_);
    CheckSizes(options.first_frame, first);
    first_ = std::move(first);
  }

  const SequenceInfo& info() const override { return info_; }

  bool Next(StereoFrame* frame) override {
    ATTEND_CHECK(frame != nullptr) << "Next needs a frame to fill";
    if (finished_) return false;
    const int index = next_index_;
    if (last_index_ >= 0 && index > last_index_) {
      finished_ = true;
      return false;
    }
    // Moving on before reading lets a caller that catches a bad frame continue after it.
    next_index_ += stride_;
    NativeFrame native;
    if (first_.has_value()) {
      native = std::move(*first_);
      first_.reset();
    } else if (!reader_->Read(index, &native)) {
      finished_ = true;
      // The source announced its length (a video's header): ending before it means frames
      // are missing, a file cut short most often. The frames before were delivered, and the
      // run keeps them; this one is an error, not a quiet end.
      if (reader_->Count() >= 0 && index < reader_->Count()) {
        throw InputError(what_ + ": ends at frame " + std::to_string(index) +
                         ", but it announces " + std::to_string(reader_->Count()) +
                         " frames (0.." + std::to_string(reader_->Count() - 1) +
                         "); the file may be cut short (the frames before were read; if its "
                         "header miscounts, set sequence.last_frame)");
      }
      return false;
    }
    CheckSizes(index, native);
    frame->index = index;
    frame->left = ToWorkingSize(native.left, info_.size);
    frame->right = native.right.empty() ? cv::Mat() : ToWorkingSize(native.right, info_.size);
    frame->left_path = std::move(native.left_path);
    frame->right_path = std::move(native.right_path);
    return true;
  }

 private:
  void CheckSizes(int index, const NativeFrame& frame) const {
    CheckFrameSizes(index, frame.left, frame.left_path, frame.right, frame.right_path,
                    info_.native_size);
  }

  std::unique_ptr<NativeReader> reader_;
  SequenceInfo info_;
  int stride_;
  int next_index_;
  int last_index_;  // inclusive; -1 while the end is unknown
  std::string what_;  // the source, for messages
  bool finished_ = false;
  std::optional<NativeFrame> first_;
};

}  // namespace

void CheckFrameSizes(int index, const cv::Mat& left, const std::string& left_path,
                     const cv::Mat& right, const std::string& right_path, cv::Size first) {
  if (left.size() != first) {
    throw InputError(FrameWhere(index, left_path) + ": size " + SizeText(left.size()) +
                     " differs from the first frame's " + SizeText(first));
  }
  if (!right.empty() && right.size() != left.size()) {
    throw InputError(FrameWhere(index, right_path) + ": size " + SizeText(right.size()) +
                     " differs from the left image's " + SizeText(left.size()));
  }
}

// Video frames are normally 8-bit BGR already; other layouts are converted the way images are.
cv::Mat VideoFrameToBgr(const cv::Mat& frame, int index, const std::string& path) {
  if (frame.depth() != CV_8U) {
    throw InputError(FrameWhere(index, path) + ": unsupported sample depth (expected 8 bits)");
  }
  if (frame.channels() == 3) return frame;
  cv::Mat bgr;
  if (frame.channels() == 1) {
    cv::cvtColor(frame, bgr, cv::COLOR_GRAY2BGR);
  } else if (frame.channels() == 4) {
    cv::cvtColor(frame, bgr, cv::COLOR_BGRA2BGR);
  } else {
    throw InputError(FrameWhere(index, path) + ": unsupported number of channels " +
                     std::to_string(frame.channels()));
  }
  return bgr;
}

cv::Size WorkingSize(const SequenceOptions& options, cv::Size native) {
  if (options.resize == "native") return native;
  if (options.resize == "stretch") return {options.width, options.height};
  // fit: the side that limits gets the box's size exactly, the other keeps the aspect ratio.
  const int64_t width_limited = static_cast<int64_t>(native.width) * options.height;
  const int64_t height_limited = static_cast<int64_t>(native.height) * options.width;
  if (width_limited >= height_limited) {
    const double height = static_cast<double>(native.height) * options.width / native.width;
    return {options.width, std::max(1, static_cast<int>(std::lround(height)))};
  }
  const double width = static_cast<double>(native.width) * options.height / native.height;
  return {std::max(1, static_cast<int>(std::lround(width))), options.height};
}

namespace {

// What the loop holds per working pixel, about: 77.6 MB at 320x240 and 99.0 MB at 640x480
// (loop_bench's peak resident set) is 93 bytes a pixel more; 150 leaves room for the dumps,
// the trackers' pyramids and larger disparity ranges.
constexpr double kLoopBytesPerPixel = 150.0;

double PhysicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES);
  const long page_size = sysconf(_SC_PAGESIZE);
  return pages > 0 && page_size > 0 ? static_cast<double>(pages) * page_size : 0.0;
}

std::string Gigabytes(double bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f GB", bytes / 1e9);
  return text;
}

}  // namespace

void SizeSequence(const SequenceOptions& options, cv::Size native, SequenceInfo* info) {
  info->native_size = native;
  info->size = WorkingSize(options, native);
  // A working size whose buffers cannot fit in this machine's memory ends in std::bad_alloc
  // (after seconds of work) or in the kernel's OOM killer: refuse it before any allocation.
  const double pixels = static_cast<double>(info->size.width) * info->size.height;
  const double needed = pixels * kLoopBytesPerPixel;
  const double memory = PhysicalMemoryBytes();
  if (memory > 0.0 && needed > memory) {
    const std::string size =
        std::to_string(info->size.width) + "x" + std::to_string(info->size.height);
    const std::string message =
        "the working size " + size + " (" + std::to_string(static_cast<int64_t>(pixels)) +
        " pixels) would need about " + Gigabytes(needed) + " (about " +
        std::to_string(static_cast<int>(kLoopBytesPerPixel)) + " bytes a pixel), more than " +
        "this machine's " + Gigabytes(memory) + " of memory";
    if (options.resize == "native") {
      throw InputError(message + "; the frames are " + std::to_string(native.width) + "x" +
                       std::to_string(native.height) +
                       ": use sequence.resize fit with a smaller sequence.width and height");
    }
    throw ConfigError(message + "; lower sequence.width and sequence.height");
  }
  info->scale_x = static_cast<double>(info->size.width) / native.width;
  info->scale_y = static_cast<double>(info->size.height) / native.height;
}

// A continuous image of `size`: area averaging when shrinking (no aliasing), bilinear when any
// side grows.
cv::Mat ToWorkingSize(const cv::Mat& image, cv::Size size) {
  if (image.size() == size) return image.isContinuous() ? image : image.clone();
  const bool shrinking = size.width <= image.cols && size.height <= image.rows;
  cv::Mat resized;
  cv::resize(image, resized, size, 0, 0, shrinking ? cv::INTER_AREA : cv::INTER_LINEAR);
  return resized;
}

const std::vector<std::string>& FrameFileExtensions() {
  static const std::vector<std::string> extensions = {".png", ".jpg", ".jpeg", ".ppm", ".pgm"};
  return extensions;
}

std::vector<std::string> ListFrameFiles(const std::string& folder, const std::string& what) {
  std::error_code error;
  if (!fs::exists(folder, error)) throw InputError(what + ": no such folder " + folder);
  if (!fs::is_directory(folder, error)) throw InputError(what + ": " + folder + " is not a folder");
  const std::vector<std::string>& extensions = FrameFileExtensions();
  std::vector<std::string> paths;
  try {
    for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
      if (!entry.is_regular_file()) continue;
      const std::string extension = Lowercase(entry.path().extension().string());
      if (std::find(extensions.begin(), extensions.end(), extension) != extensions.end()) {
        paths.push_back(entry.path().string());
      }
    }
  } catch (const fs::filesystem_error& e) {
    throw InputError(what + ": cannot list the frames in " + folder + ": " + e.what());
  }
  // By file name, byte by byte: the position in this list is the frame index.
  std::sort(paths.begin(), paths.end(), [](const std::string& a, const std::string& b) {
    return fs::path(a).filename().string() < fs::path(b).filename().string();
  });
  return paths;
}

cv::Mat ReadFrameFile(int index, const std::string& path) {
  // IMREAD_COLOR turns grey into three equal channels and 16-bit samples into 8-bit ones (the
  // high byte), so every later stage sees CV_8UC3.
  return ReadImageFile(path, cv::IMREAD_COLOR, FrameWhere(index, path));
}

const std::vector<std::string>& SequenceOptions::ResizeModes() {
  static const std::vector<std::string> modes = {"fit", "stretch", "native"};
  return modes;
}

int SequenceOptions::SourceCount() const {
  const bool has_pair = !left_video.empty() || !right_video.empty();
  return (folder.empty() ? 0 : 1) + (has_pair ? 1 : 0) + (side_by_side_video.empty() ? 0 : 1) +
         (video.empty() ? 0 : 1) + (images.empty() ? 0 : 1) + (IsLive() ? 1 : 0);
}

bool SequenceOptions::IsLive() const {
  return camera >= 0 || camera_right >= 0 || !gst.empty() || !gst_right.empty();
}

const OptionFields<SequenceOptions>& SequenceOptions::Fields() {
  using O = SequenceOptions;
  static const OptionFields<SequenceOptions> fields = {
      {"folder", &O::folder, "sequence folder with left/ and right/ (or left/ alone)"},
      {"left_video", &O::left_video, "left video of a stereo pair (with right_video)"},
      {"right_video", &O::right_video, "right video of a stereo pair"},
      {"side_by_side_video", &O::side_by_side_video, "one video, the left view in its left half"},
      {"video", &O::video, "a monocular video"},
      {"images", &O::images, "a plain folder of frames, monocular, in sorted name order"},
      {"camera", &O::camera, Range::Closed(-1, 4095), "a live V4L2 camera /dev/videoN; -1: none"},
      {"camera_right", &O::camera_right, Range::Closed(-1, 4095),
       "the right camera of a live stereo pair; -1: none"},
      {"gst", &O::gst, "a live GStreamer pipeline (ending in an appsink)"},
      {"gst_right", &O::gst_right, "the right pipeline of a live stereo pair"},
      {"first_frame", &O::first_frame, Range::Closed(0, 1e9), "first frame of the range"},
      {"last_frame", &O::last_frame, Range::Closed(-1, 1e9),
       "last frame of the range, inclusive; -1: to the end"},
      {"stride", &O::stride, Range::Closed(1, 1e6), "take every n-th frame of the range"},
      {"width", &O::width, Range::AboveUpTo(0, 16384), "working width, px"},
      {"height", &O::height, Range::AboveUpTo(0, 16384), "working height, px"},
      {"resize", &O::resize, "fit: keep the aspect ratio; stretch: exactly; native: no scaling",
       &SequenceOptions::ResizeModes}};
  return fields;
}

std::string SequenceOptions::Check() const {
  const bool has_pair = !left_video.empty() || !right_video.empty();
  const int sources = SourceCount();
  // No source is valid here: `attend run` then takes the bundled sequence. Open() needs one.
  if (sources > 1) {
    return "at most one source may be set (folder, left_video + right_video, "
           "side_by_side_video, video, images, or a live camera or gst), got " +
           std::to_string(sources);
  }
  if (has_pair && (left_video.empty() || right_video.empty())) {
    return left_video.empty() ? "left_video must be set together with right_video"
                              : "right_video must be set together with left_video";
  }
  // The working size is checked below, and only unless resize is native.
  SequenceOptions sized = *this;
  sized.width = SequenceOptions().width;
  sized.height = SequenceOptions().height;
  const std::string error = CheckFieldRanges(sized, Fields());
  if (!error.empty()) return error;
  const std::string live_error = CheckLiveSource(*this);
  if (!live_error.empty()) return live_error;
  if (last_frame != -1 && last_frame < first_frame) {
    return "last_frame must be -1 (to the end) or >= first_frame (" + std::to_string(first_frame) +
           "), got " + std::to_string(last_frame);
  }
  if (resize != "native") {
    for (const auto& [name, side] : {std::pair<const char*, int>{"width", width}, {"height", height}}) {
      const Range& range = RangeOf(Fields(), name);
      if (!range.Contains(side)) {
        return std::string(name) + " " + range.DescribeBreach(side) +
               " unless resize is native, got " + std::to_string(side);
      }
    }
  }
  return "";
}

std::string SequenceOptions::Describe() const {
  if (!folder.empty()) return "folder " + folder;
  if (!left_video.empty() || !right_video.empty()) {
    return "videos " + left_video + " + " + right_video;
  }
  if (!side_by_side_video.empty()) return "side-by-side video " + side_by_side_video;
  if (!video.empty()) return "video " + video;
  if (!images.empty()) return "images " + images;
  if (IsLive()) return DescribeLiveSource(*this);
  return "no source";
}

namespace {

// ReadAhead's source: a worker thread runs the wrapped source's Next() for the frame after the
// one last handed out, and waits until that one is taken.
class ReadAheadSource final : public FrameSource {
 public:
  explicit ReadAheadSource(std::unique_ptr<FrameSource> source)
      : source_(std::move(source)), worker_([this] { Work(); }) {
    Request();
  }

  ~ReadAheadSource() override {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      quit_ = true;
    }
    changed_.notify_all();
    worker_.join();
  }

  const SequenceInfo& info() const override { return source_->info(); }

  bool Next(StereoFrame* frame) override {
    ATTEND_CHECK(frame != nullptr) << "Next needs a frame to fill";
    Result result;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (ended_) {
        // The source ended at the last call; ask it again, as a caller of it would.
        requested_ = true;
        changed_.notify_all();
      }
      changed_.wait(lock, [this] { return ready_; });
      ready_ = false;
      result = std::move(result_);
      // Read on after a frame or a bad frame, not after the end.
      ended_ = !result.more;
      if (result.more) {
        requested_ = true;
        changed_.notify_all();
      }
    }
    if (result.error) std::rethrow_exception(result.error);
    if (!result.more) return false;
    *frame = std::move(result.frame);
    return true;
  }

 private:
  struct Result {
    StereoFrame frame;
    bool more = false;  // a frame (or a bad one) rather than the end
    std::exception_ptr error;
  };

  void Request() {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      requested_ = true;
    }
    changed_.notify_all();
  }

  void Work() {
    std::unique_lock<std::mutex> lock(mutex_);
    while (true) {
      changed_.wait(lock, [this] { return quit_ || requested_; });
      if (quit_) return;
      requested_ = false;
      lock.unlock();
      Result result;
      try {
        result.more = source_->Next(&result.frame);
      } catch (...) {
        result.error = std::current_exception();
        result.more = true;
      }
      lock.lock();
      result_ = std::move(result);
      ready_ = true;
      changed_.notify_all();
    }
  }

  std::unique_ptr<FrameSource> source_;
  std::mutex mutex_;
  std::condition_variable changed_;
  bool requested_ = false;  // the worker is to read the next frame
  bool ready_ = false;      // result_ holds what it read, not yet taken
  bool ended_ = false;      // the last result taken was the end of the source
  bool quit_ = false;
  Result result_;
  std::thread worker_;  // last: starts once the members it uses exist
};

}  // namespace

std::unique_ptr<FrameSource> ReadAhead(std::unique_ptr<FrameSource> source) {
  ATTEND_CHECK(source != nullptr) << "ReadAhead needs a source";
  return std::make_unique<ReadAheadSource>(std::move(source));
}

std::unique_ptr<FrameSource> FrameSource::Open(const SequenceOptions& options) {
  if (options.SourceCount() == 0) {
    throw ConfigError(
        "no sequence source is set (folder, left_video + right_video, "
        "side_by_side_video, video, images, camera or gst)");
  }
  const std::string problem = options.Check();
  if (!problem.empty()) throw ConfigError("sequence options: " + problem);
  if (options.IsLive()) return OpenLiveSource(options);
  SequenceInfo info;
  std::unique_ptr<NativeReader> reader;
  if (!options.folder.empty()) {
    reader = std::make_unique<FolderReader>(options, &info);
  } else if (!options.images.empty()) {
    reader = std::make_unique<ImageFolderReader>(options, &info);
  } else {
    reader = std::make_unique<VideoReader>(options, &info);
  }
  return std::make_unique<Sequence>(options, std::move(reader), std::move(info));
}

}  // namespace attend
