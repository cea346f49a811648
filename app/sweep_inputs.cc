#include "app/sweep_inputs.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <set>

#include "app/run_attention.h"
#include "io/kitti_layout.h"
#include "util/error.h"
#include "util/file_checks.h"
#include "util/frame_range.h"
#include "util/output_folder.h"
#include "util/strings.h"

namespace attend {

namespace {

// A KITTI raw drive or tracking sequence with its labels, which attend eval reads itself.
bool HasKittiLabels(const std::string& folder) {
  const std::optional<KittiSequence> kitti = FindKittiSequence(folder);
  return kitti.has_value() && !kitti->labels.empty();
}

namespace fs = std::filesystem;

const std::vector<std::string>& InputKeys() {
  static const std::vector<std::string> keys = {
      "name",      "sequence", "video", "images", "left", "right", "side_by_side",
      "fixations", "scene",    "gt",    "frames", "skip", "first"};
  return keys;
}

// The source kinds an input may name (one of them), and `right` beside `left`.
const std::vector<std::string>& SourceKinds() {
  static const std::vector<std::string> kinds = {"sequence",     "video",     "images", "left",
                                                 "side_by_side", "fixations", "scene"};
  return kinds;
}

// Kinds whose path is a folder; the others name a file.
bool IsFolderKind(const std::string& kind) {
  return kind == "sequence" || kind == "images" || kind == "fixations";
}

// The folder a scene renders into: DIR/scenes/<stem>-<FNV-1a of the scene file's text>, so a
// changed scene renders anew.
std::string SceneFolder(const std::string& scene, const std::string& dir) {
  char hash[17];
  std::snprintf(hash, sizeof(hash), "%016llx",
                static_cast<unsigned long long>(Fnv1a(
                    ReadRegularFile(scene, "the scene", ExitStatus::kUsage, kMaxConfigBytes))));
  return (fs::path(dir.empty() ? "SWEEP_DIR" : dir) / "scenes" /
          (fs::path(scene).stem().string() + "-" + hash))
      .lexically_normal()
      .string();
}

// An entry's source: its one kind key, the path (which must exist), a scene's folder, and the
// right video beside `left`. Returns the source's node, for the errors that follow.
YAML::Node ReadSource(const YamlDocument& document, const YAML::Node& node, const std::string& path,
                      SweepCommand command, const std::string& dir, SweepInput* input) {
  std::vector<std::string> kinds;
  for (const std::string& kind : SourceKinds()) {
    if (node[kind]) kinds.push_back(kind);
  }
  if (kinds.size() != 1) {
    document.Fail(node, path,
                  kinds.empty() ? "names no source: give one of " + Join(SourceKinds(), ", ")
                                : "names " + Join(kinds, " and ") + ": give one source an input");
  }
  input->kind = kinds[0];
  const YAML::Node source = node[input->kind];
  const std::string key = path + "." + input->kind;
  input->path = document.Path(source, key);
  const bool folder = IsFolderKind(input->kind);
  std::error_code error;
  if (folder ? !fs::is_directory(input->path, error) : !fs::is_regular_file(input->path, error)) {
    document.Fail(source, key, input->path + ": no such " + (folder ? "folder" : "file"));
  }
  if (input->kind == "scene") {
    if (command != SweepCommand::kRun) document.Fail(source, key, "scenes are for command run");
    input->scene = input->path;
    input->path = SceneFolder(input->scene, dir);
  }
  if (node["right"]) {
    if (input->kind != "left") document.Fail(node["right"], path + ".right", "only beside left");
    input->right = document.Path(node["right"], path + ".right");
    if (!fs::is_regular_file(input->right, error)) {
      document.Fail(node["right"], path + ".right", input->right + ": no such file");
    }
  } else if (input->kind == "left") {
    document.Fail(node, path, "left needs right (a left/right pair of videos)");
  }
  return source;
}

// The entry's frames, a fixation dataset's split and its ground truth's path.
void ReadInputOptions(const YamlDocument& document, const YAML::Node& node, const std::string& path,
                      SweepInput* input) {
  if (node["frames"]) {
    input->frames = document.String(node["frames"], path + ".frames");
    if (input->kind == "fixations") {
      document.Fail(node["frames"], path + ".frames",
                    "frames is not for fixation datasets (use skip and first)");
    }
    // Checked here, as --frames checks it, instead of failing every cell of the input.
    try {
      ParseFrameRange(input->frames);
    } catch (const ConfigError& e) {
      document.Fail(node["frames"], path + ".frames", e.what());
    }
  }
  if (node["skip"] || node["first"]) {
    if (input->kind != "fixations") {
      document.Fail(node["skip"] ? node["skip"] : node["first"], path,
                    "skip and first are for fixation datasets");
    }
    if (node["skip"]) input->skip = document.Int(node["skip"], path + ".skip", 0, 1000000);
    if (node["first"]) input->first = document.Int(node["first"], path + ".first", 0, 1000000);
  }
  if (node["gt"]) input->gt = document.Path(node["gt"], path + ".gt");
}

// What each command takes, and its ground truth.
void CheckInputForCommand(const YamlDocument& document, const YAML::Node& node,
                          const YAML::Node& source, const std::string& path, SweepCommand command,
                          const SweepInput& input) {
  const std::string key = path + "." + input.kind;
  std::error_code error;
  if (command == SweepCommand::kSaliency) {
    if (input.kind != "fixations") {
      document.Fail(source, key, "command saliency takes fixation datasets (fixations: FOLDER)");
    }
    if (!input.gt.empty()) document.Fail(node["gt"], path + ".gt", "a fixation dataset is its gt");
  } else if (input.kind == "fixations") {
    document.Fail(source, key, "a fixation dataset needs command: saliency");
  }
  if (command == SweepCommand::kTrack) {
    if (input.kind != "images" && input.kind != "sequence") {
      document.Fail(source, key, "command track takes images or sequence folders");
    }
    if (input.gt.empty()) {
      document.Fail(node, path, "command track needs gt: an OTB groundtruth_rect.txt");
    }
    if (!fs::is_regular_file(input.gt, error)) {
      document.Fail(node["gt"], path + ".gt", input.gt + ": no such file");
    }
  }
  // attend eval's ground truth: the input's gt:, else a sequence's own gt/ (a rendered scene
  // brings its own, a KITTI sequence its labels).
  if (command == SweepCommand::kRun && !(input.kind == "scene" && input.gt.empty()) &&
      !(input.kind == "sequence" && input.gt.empty() && HasKittiLabels(input.path))) {
    const std::string gt =
        !input.gt.empty()
            ? input.gt
            : (input.kind == "sequence" ? (fs::path(input.path) / "gt").string() : "");
    if (gt.empty()) {
      document.Fail(node, path,
                    "attend eval needs ground truth: give gt: (a folder holding objects.csv)");
    }
    if (!fs::is_regular_file(fs::path(gt) / "objects.csv", error)) {
      document.Fail(node["gt"] ? node["gt"] : source, node["gt"] ? path + ".gt" : key,
                    gt + ": no objects.csv (the ground truth attend eval scores against)");
    }
  }
}

// The entry's name: given, else its source's file or folder name.
std::string InputName(const YamlDocument& document, const YAML::Node& node, const std::string& path,
                      const SweepInput& input) {
  std::string name;
  if (node["name"]) {
    name = document.String(node["name"], path + ".name");
  } else {
    fs::path named(input.kind == "scene" ? input.scene : input.path);
    // An OTB sequence's frames are in NAME/img.
    if (named.filename() == "img" && named.has_parent_path()) named = named.parent_path();
    name = named.filename().string();
    if (input.kind == "video" || input.kind == "left" || input.kind == "side_by_side" ||
        input.kind == "scene") {
      name = named.stem().string();
    }
  }
  name = FileSafe(name, 40);
  if (name.empty()) document.Fail(node, path + ".name", "no usable name: give name:");
  return name;
}

SweepInput ReadInput(const YamlDocument& document, const YAML::Node& node, std::size_t index,
                     SweepCommand command, const std::string& dir) {
  const std::string path = "inputs[" + std::to_string(index) + "]";
  if (!node.IsMap()) document.Fail(node, path, "expected a map such as {sequence: FOLDER}");
  document.CheckKeys(node, path, InputKeys());
  SweepInput input;
  input.where = document.At(node);
  const YAML::Node source = ReadSource(document, node, path, command, dir, &input);
  ReadInputOptions(document, node, path, &input);
  CheckInputForCommand(document, node, source, path, command, input);
  input.name = InputName(document, node, path, input);
  return input;
}

}  // namespace

const char* SweepCommandName(SweepCommand command) {
  switch (command) {
    case SweepCommand::kRun:
      return "run";
    case SweepCommand::kTrack:
      return "track";
    case SweepCommand::kSaliency:
      return "saliency";
  }
  return "run";
}

std::vector<SweepInput> ReadSweepInputs(const YamlDocument& document, SweepCommand command,
                                        const std::string& dir) {
  const YAML::Node inputs = document.root()["inputs"];
  if (!inputs || inputs.IsNull()) {
    throw ConfigError(document.file() +
                      ": inputs: missing: give the sequences, videos, image folders "
                      "or fixation datasets to run on");
  }
  if (!inputs.IsSequence() || inputs.size() == 0) {
    document.Fail(inputs, "inputs", "expected a non-empty list of inputs");
  }
  std::vector<SweepInput> read;
  std::set<std::string> names;
  for (std::size_t i = 0; i < inputs.size(); ++i) {
    read.push_back(ReadInput(document, inputs[i], i, command, dir));
    if (!names.insert(read.back().name).second) {
      document.Fail(inputs[i], "inputs[" + std::to_string(i) + "]",
                    "a second input named '" + read.back().name + "': give each a name:");
    }
  }
  return read;
}

SourceSpec InputSource(const SweepInput& input) {
  SourceSpec source;
  if (input.kind == "sequence" || input.kind == "scene") source.folder = input.path;
  if (input.kind == "left") source.left_video = input.path;
  source.right_video = input.right;
  if (input.kind == "side_by_side") source.side_by_side_video = input.path;
  if (input.kind == "video") source.video = input.path;
  if (input.kind == "images") source.images = input.path;
  return source;
}

std::vector<std::string> SourceArguments(const SweepInput& input) {
  return RunSourceArguments(InputSource(input));
}

std::string FileSafe(const std::string& text, std::size_t max_length) {
  std::string out;
  for (const char c : text) {
    const bool keep = std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' ||
                      c == '=' || c == '+' || c == '-';
    if (keep) {
      out += c;
    } else if (out.empty() || out.back() != '-') {
      out += '-';
    }
  }
  while (!out.empty() && (out.front() == '-' || out.front() == '.')) out.erase(out.begin());
  if (out.size() > max_length) out.resize(max_length);
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out;
}

}  // namespace attend
