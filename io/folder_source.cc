#include "io/folder_source.h"

#include <algorithm>
#include <filesystem>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "config/param_block.h"
#include "config/read_fields.h"
#include "io/frame_files.h"
#include "io/ranged_source.h"
#include "util/error.h"
#include "util/strings.h"

namespace attend {

namespace fs = std::filesystem;

namespace {

// The last non-empty component of a path ("data/seq/" -> "seq").
std::string FolderStem(const std::string& folder) {
  fs::path path = fs::absolute(fs::path(folder)).lexically_normal();
  if (path.filename().empty()) path = path.parent_path();
  return path.filename().string();
}

// The keys of SEQ/sequence.yaml that attend reads (docs/SEQUENCES.md).
struct SequenceFile {
  std::string name;
  double fps = 25.0;
  double focal_px = 0.0;
  double baseline_m = 0.0;

  static const OptionFields<SequenceFile>& Fields() {
    using F = SequenceFile;
    static const OptionFields<F> fields = {
        {"name", &F::name, "the sequence's name; the folder's when absent"},
        {"fps", &F::fps, Range::Above(0), "frames a second"},
        {"focal_px", &F::focal_px, Range::AtLeast(0), "the focal length, pixels; 0 unknown"},
        {"baseline_m", &F::baseline_m, Range::AtLeast(0),
         "the stereo baseline, metres; 0 unknown"}};
    return fields;
  }
};

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
  FolderReader(const SourceSpec& source, SequenceInfo* info) {
    const fs::path folder(source.folder);
    const std::string what = source.Describe();
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
    info->name = FolderStem(source.folder);
    info->folder = source.folder;
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
  ImageFolderReader(const SourceSpec& source, SequenceInfo* info) {
    const std::string what = source.Describe();
    files_ = ListFrameFiles(source.images, what);
    if (files_.empty()) {
      throw InputError(what + ": no frames (expected files ending in " +
                       Join(FrameFileExtensions(), ", ") + "); the folder holds no images");
    }
    info->stereo = false;
    info->name = FolderStem(source.images);
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

}  // namespace

void ReadSequenceYaml(const std::string& path, SequenceInfo* info) {
  try {
    const ParamBlock block = ParamBlock::LoadFile(path);
    SequenceFile file;
    file.name = info->name;
    file.fps = info->fps;
    ReadFields(block, SequenceFile::Fields(), &file);
    if (file.name.empty()) block.Fail("name", "must not be empty");
    info->name = file.name;
    info->fps = file.fps;
    info->focal_px = file.focal_px;
    info->baseline_m = file.baseline_m;
    block.Accept("generator");
    block.Accept("frames");
    block.CheckNoUnknownKeys();
  } catch (const ConfigError& e) {
    throw InputError(e.what());
  }
}

std::unique_ptr<FrameSource> OpenFolderSource(const SequenceOptions& options) {
  SequenceInfo info;
  auto reader = std::make_unique<FolderReader>(options.source, &info);
  return OpenRangedSource(options, std::move(reader), std::move(info));
}

std::unique_ptr<FrameSource> OpenImageFolderSource(const SequenceOptions& options) {
  SequenceInfo info;
  auto reader = std::make_unique<ImageFolderReader>(options.source, &info);
  return OpenRangedSource(options, std::move(reader), std::move(info));
}

}  // namespace attend
