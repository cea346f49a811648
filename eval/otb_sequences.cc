#include "eval/otb_sequences.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <system_error>

#include "io/frame_files.h"
#include "io/tracking_files.h"
#include "util/error.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

// The benchmark's attributes in its order (Wu, Lim and Yang, TPAMI 2015, table 1).
struct Attribute {
  const char* code;
  const char* name;
};
constexpr Attribute kAttributes[] = {{"IV", "Illumination Variation"},
                                     {"SV", "Scale Variation"},
                                     {"OCC", "Occlusion"},
                                     {"DEF", "Deformation"},
                                     {"MB", "Motion Blur"},
                                     {"FM", "Fast Motion"},
                                     {"IPR", "In-Plane Rotation"},
                                     {"OPR", "Out-of-Plane Rotation"},
                                     {"OV", "Out-of-View"},
                                     {"BC", "Background Clutters"},
                                     {"LR", "Low Resolution"}};
constexpr int kAttributeCount = sizeof(kAttributes) / sizeof(kAttributes[0]);

int AttributeRank(const std::string& code) {
  for (int i = 0; i < kAttributeCount; ++i) {
    if (code == kAttributes[i].code) return i;
  }
  return kAttributeCount;
}

// A ground-truth file of a sequence folder, and the suffix its sequence's name takes.
struct TruthFile {
  std::string path;
  std::string suffix;  // "" for groundtruth_rect.txt, "-N" for groundtruth_rect.N.txt
  int number = 0;
};

// groundtruth_rect.txt and groundtruth_rect.N.txt (N digits), by N.
std::vector<TruthFile> TruthFiles(const fs::path& folder) {
  std::vector<TruthFile> files;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
    if (!entry.is_regular_file(error)) continue;
    const std::string name = entry.path().filename().string();
    if (name == "groundtruth_rect.txt") {
      files.push_back({entry.path().string(), "", -1});
      continue;
    }
    const std::string head = "groundtruth_rect.", tail = ".txt";
    if (name.size() <= head.size() + tail.size() || name.rfind(head, 0) != 0 ||
        name.compare(name.size() - tail.size(), tail.size(), tail) != 0) {
      continue;
    }
    const std::string digits = name.substr(head.size(), name.size() - head.size() - tail.size());
    if (digits.size() > 6 || !std::all_of(digits.begin(), digits.end(),
                                          [](unsigned char c) { return std::isdigit(c); })) {
      continue;
    }
    files.push_back({entry.path().string(), "-" + digits, std::stoi(digits)});
  }
  std::sort(files.begin(), files.end(),
            [](const TruthFile& a, const TruthFile& b) { return a.number < b.number; });
  return files;
}

// What a sequence folder's cfg.json says, where it says it.
struct SequenceConfig {
  std::optional<int> start_frame;  // 1-based
  std::optional<int> end_frame;    // 1-based, inclusive
  std::vector<std::string> attributes;
};

int FrameNumber(const nlohmann::json& value, const std::string& path, const char* key) {
  if (!value.is_number_integer() || value.get<long long>() < 1 ||
      value.get<long long>() > 100000000) {
    throw InputError(path + ": " + key + " must be a whole number >= 1, got " + value.dump());
  }
  return value.get<int>();
}

SequenceConfig ReadSequenceConfig(const fs::path& folder) {
  SequenceConfig config;
  const std::string path = (folder / "cfg.json").string();
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return config;
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the sequence's cfg.json");
  nlohmann::json json;
  try {
    json = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path + ": not valid JSON (" + std::string(e.what()) + ")");
  }
  if (!json.is_object()) throw InputError(path + ": expected a JSON object");
  if (json.contains("startFrame")) {
    config.start_frame = FrameNumber(json["startFrame"], path, "startFrame");
  }
  if (json.contains("endFrame")) config.end_frame = FrameNumber(json["endFrame"], path, "endFrame");
  if (json.contains("attributes")) {
    const nlohmann::json& attributes = json["attributes"];
    if (!attributes.is_array()) throw InputError(path + ": attributes must be a list of codes");
    for (const nlohmann::json& code : attributes) {
      if (!code.is_string()) {
        throw InputError(path + ": attributes must be a list of codes, got " + code.dump());
      }
      config.attributes.push_back(code.get<std::string>());
    }
  }
  return config;
}

// attrs.txt: codes separated by commas (spaces and line breaks around them are ignored).
std::optional<std::vector<std::string>> ReadAttributesFile(const fs::path& folder) {
  const std::string path = (folder / "attrs.txt").string();
  std::error_code error;
  if (!fs::is_regular_file(path, error)) return std::nullopt;
  std::ifstream in(path);
  if (!in) throw InputError(path + ": cannot read the attributes");
  std::stringstream text;
  text << in.rdbuf();
  std::vector<std::string> codes;
  std::string code;
  for (const char c : text.str() + ",") {
    if (c == ',' || c == '\n' || c == '\r') {
      const size_t begin = code.find_first_not_of(" \t");
      if (begin != std::string::npos) {
        codes.push_back(code.substr(begin, code.find_last_not_of(" \t") - begin + 1));
      }
      code.clear();
    } else {
      code += c;
    }
  }
  return codes;
}

std::vector<std::string> Normalised(std::vector<std::string> codes) {
  std::vector<std::string> out;
  for (std::string& code : codes) {
    for (char& c : code) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
    if (!code.empty() && std::find(out.begin(), out.end(), code) == out.end()) out.push_back(code);
  }
  return out;
}

// The frames of one ground-truth file: the images from startFrame to endFrame that have a line.
OtbSequence ReadSequence(const fs::path& folder, const TruthFile& file,
                         const SequenceConfig& config, const std::vector<std::string>& images,
                         const std::vector<std::string>& attributes) {
  OtbSequence sequence;
  // "SEQ/", "SEQ/." and "." name the folder they stand for.
  fs::path named = fs::absolute(folder).lexically_normal();
  if (named.filename().empty()) named = named.parent_path();
  sequence.folder_name = named.filename().string();
  sequence.name = sequence.folder_name + file.suffix;
  sequence.folder = folder.string();
  sequence.ground_truth = file.path;
  sequence.attributes = attributes;
  const std::vector<cv::Rect2d> boxes = ReadOtbGroundTruth(file.path);
  const std::string cfg = (folder / "cfg.json").string();
  const int count = static_cast<int>(images.size());
  const int start = config.start_frame.value_or(1);
  if (start > count) {
    throw InputError(cfg + ": startFrame " + std::to_string(start) + " is beyond the " +
                     std::to_string(count) + " images of " + (folder / "img").string());
  }
  int end = config.end_frame.value_or(count);
  if (end < start) {
    throw InputError(cfg + ": endFrame " + std::to_string(end) + " is before startFrame " +
                     std::to_string(start));
  }
  if (end > count) {
    sequence.notes.push_back(sequence.name + ": " + cfg + " ends at frame " + std::to_string(end) +
                             ", img/ has " + std::to_string(count) +
                             " images; the last image ends it");
    end = count;
  }
  const int available = end - start + 1;
  const int frames = std::min(available, static_cast<int>(boxes.size()));
  if (available != static_cast<int>(boxes.size())) {
    sequence.notes.push_back(sequence.name + ": " + std::to_string(available) + " images, " +
                             std::to_string(boxes.size()) + " boxes in " + file.path +
                             "; the first " + std::to_string(frames) + " frames are scored");
  }
  if (boxes[0].empty()) {
    throw InputError(file.path +
                     ":1: no box on the first frame (w or h 0, or NaN); the one-pass "
                     "evaluation starts every tracker from it");
  }
  sequence.first_image = start - 1;
  sequence.images.assign(images.begin() + (start - 1), images.begin() + (start - 1) + frames);
  sequence.truth.assign(boxes.begin(), boxes.begin() + frames);
  return sequence;
}

// The sequences of one sequence folder: one per ground-truth file.
std::vector<OtbSequence> ReadSequenceFolder(const fs::path& folder) {
  const std::vector<TruthFile> files = TruthFiles(folder);
  const SequenceConfig config = ReadSequenceConfig(folder);
  const std::optional<std::vector<std::string>> listed = ReadAttributesFile(folder);
  const std::vector<std::string> attributes = Normalised(listed ? *listed : config.attributes);
  const std::string img = (folder / "img").string();
  const std::vector<std::string> images = ListFrameFiles(img, "sequence " + folder.string());
  if (images.empty()) throw InputError(img + ": no image (png, jpg, jpeg, ppm or pgm)");
  std::vector<OtbSequence> sequences;
  for (const TruthFile& file : files) {
    // A single file named groundtruth_rect.N.txt still names the sequence FOLDER-N, as the
    // toolkit does (Human4-2).
    sequences.push_back(ReadSequence(folder, file, config, images, attributes));
  }
  return sequences;
}

}  // namespace

bool IsOtbSequenceFolder(const std::string& folder) {
  std::error_code error;
  return fs::is_directory(fs::path(folder) / "img", error) && !TruthFiles(folder).empty();
}

std::vector<OtbSequence> FindOtbSequences(const std::string& dir, std::vector<std::string>* notes) {
  std::error_code error;
  if (!fs::exists(dir, error)) throw InputError(dir + ": no such folder");
  if (!fs::is_directory(dir, error)) throw InputError(dir + ": not a folder");
  if (IsOtbSequenceFolder(dir)) return ReadSequenceFolder(dir);

  std::vector<fs::path> folders;
  try {
    for (const fs::directory_entry& entry : fs::directory_iterator(dir)) {
      if (entry.is_directory()) folders.push_back(entry.path());
    }
  } catch (const fs::filesystem_error& e) {
    throw InputError(dir + ": cannot list its folders (" + std::string(e.what()) + ")");
  }
  std::sort(folders.begin(), folders.end());
  std::vector<OtbSequence> sequences;
  for (const fs::path& folder : folders) {
    if (IsOtbSequenceFolder(folder.string())) {
      for (OtbSequence& sequence : ReadSequenceFolder(folder)) sequences.push_back(sequence);
    } else if (notes != nullptr && fs::is_directory(folder / "img", error)) {
      notes->push_back(folder.string() + ": an img/ folder but no groundtruth_rect.txt: skipped");
    }
  }
  if (sequences.empty()) {
    throw InputError(dir +
                     ": no OTB sequence in it (a folder with img/ and groundtruth_rect.txt "
                     "or groundtruth_rect.N.txt), nor in its sub-folders");
  }
  return sequences;
}

std::string OtbAttributeName(const std::string& code) {
  const int rank = AttributeRank(code);
  return rank < kAttributeCount ? kAttributes[rank].name : code;
}

bool OtbAttributeBefore(const std::string& a, const std::string& b) {
  const int rank_a = AttributeRank(a), rank_b = AttributeRank(b);
  return rank_a != rank_b ? rank_a < rank_b : a < b;
}

}  // namespace attend
