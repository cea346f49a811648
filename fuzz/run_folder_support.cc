#include "fuzz/run_folder_support.h"

#include <filesystem>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "fuzz/fuzz_support.h"
#include "io/pfm.h"
#include "pipeline/options_io.h"

namespace attend::fuzz {

namespace fs = std::filesystem;

namespace {

TargetRecord Target(int id, cv::Rect box, TargetState state, const std::string& kind) {
  TargetRecord target;
  target.id = id;
  target.bbox = box;
  target.area = box.area() * 3 / 4;
  target.saliency = 0.5 + 0.1 * id;
  target.state = state;
  target.kind = kind;
  target.similarity = kind == "skin" ? "skin" : "hsv";
  return target;
}

// A map that differs from frame to frame and from run to run (`offset`).
cv::Mat SaliencyMap(int frame, float offset) {
  cv::Mat map(kRunHeight, kRunWidth, CV_32FC1);
  for (int y = 0; y < map.rows; ++y) {
    for (int x = 0; x < map.cols; ++x) {
      map.at<float>(y, x) = static_cast<float>((x * 7 + y * 3 + frame * 5) % 17) / 16.0f + offset;
    }
  }
  return map / (1.0f + offset);
}

void MakeParent(const std::string& path) {
  std::error_code error;
  fs::create_directories(fs::path(path).parent_path(), error);
}

}  // namespace

std::vector<FrameRecord> ValidFrames() {
  std::vector<FrameRecord> frames(3);
  for (int i = 0; i < 3; ++i) {
    FrameRecord& record = frames[i];
    record.frame = i;
    const TargetState state = i == 0 ? TargetState::kNew : TargetState::kTracked;
    record.targets.push_back(Target(1, cv::Rect(4 + i, 4, 10, 8), state, "object"));
    if (i >= 1) {
      record.targets.push_back(Target(2, cv::Rect(18, 10, 9, 9),
                                      i == 1 ? TargetState::kNew : TargetState::kOccluded, "skin"));
    }
    if (i == 0) record.new_ids = {1};
    if (i == 1) record.new_ids = {2};
    record.inhibited_fraction = 0.1 * i;
    record.timings.Add("features", 1.5 + i);
    record.timings.Add("saliency", 0.25);
    record.timings.Add("attention", 0.75);
  }
  return frames;
}

std::vector<GtObject> ValidObjects() {
  std::vector<GtObject> objects;
  for (int frame = 0; frame < 3; ++frame) {
    GtObject object;
    object.frame = frame;
    object.id = 1;
    object.box = cv::Rect2d(4.5 + frame, 4, 10, 8.5);
    object.visible_fraction = 1.0;
    object.disparity = 6.0;
    objects.push_back(object);
    GtObject skin;
    skin.frame = frame;
    skin.id = 2;
    skin.box = cv::Rect2d(18, 10, 9, 9);
    skin.visible_fraction = frame == 2 ? 0.0 : 0.75;
    skin.kind = "skin";
    objects.push_back(skin);
  }
  return objects;
}

RunFiles ValidRunFiles(const std::string& sequence) {
  RunFiles files;
  for (const FrameRecord& record : ValidFrames()) {
    files.frames_jsonl += FrameRecordToJson(record) + "\n";
  }
  AttendOptions options;
  options.sequence.source.folder = sequence;
  options.output.dump = {"overlay", "features", "saliency"};
  files.config_yaml = OptionsToYaml(options);
  const nlohmann::ordered_json size = {kRunWidth, kRunHeight};
  const nlohmann::ordered_json summary = {
      {"frames", 3},
      {"fps", 50.0},
      {"timings_ms", {{"features", 2.5}, {"saliency", 0.25}, {"attention", 0.75}}},
      {"targets_attended", 2},
      {"tracker", "bip"},
      {"interrupted", false},
      {"error", nullptr},
      {"sequence",
       {{"name", "fuzz"},
        {"source", "folder " + sequence},
        {"stereo", true},
        {"frames_in_range", 3},
        {"native_size", size},
        {"size", size}}},
      {"pixels",
       {{"records", "input"},
        {"maps", "working"},
        {"input_size", size},
        {"working_size", size},
        {"input_from_working", {1.0, 1.0}}}}};
  files.summary_json = summary.dump(2) + "\n";
  return files;
}

void WriteGroundTruth(const std::string& sequence) {
  const std::string objects = sequence + "/gt/objects.csv";
  MakeParent(objects);
  WriteObjectsCsv(objects, ValidObjects());
  for (int frame = 0; frame < 3; ++frame) {
    const std::string path = GtDisparityPath(sequence, frame);
    MakeParent(path);
    cv::Mat disparity(kRunHeight, kRunWidth, CV_32FC1, cv::Scalar(6.0f + frame));
    disparity.at<float>(0, 0) = std::numeric_limits<float>::infinity();  // Middlebury's unknown
    WritePfm(path, disparity);
  }
}

void WriteRunFiles(const std::string& dir, const RunFiles& files) {
  WriteFile(dir + "/frames.jsonl", files.frames_jsonl);
  WriteFile(dir + "/config.yaml", files.config_yaml);
  WriteFile(dir + "/summary.json", files.summary_json);
}

void WriteRunFolder(const std::string& dir, const RunFiles& files) {
  WriteRunFiles(dir, files);
  const float offset = static_cast<float>(std::hash<std::string>{}(dir) % 5) / 10.0f;
  for (int frame = 0; frame < 3; ++frame) {
    const std::string stem = FrameStem(frame);
    const cv::Mat saliency = SaliencyMap(frame, offset);
    const std::string pfm = dir + "/saliency/" + stem + ".pfm";
    MakeParent(pfm);
    WritePfm(pfm, saliency);
    cv::Mat preview;
    saliency.convertTo(preview, CV_8UC1, 255.0);
    cv::imwrite(dir + "/saliency/" + stem + ".png", preview);
    const std::string disparity = dir + "/features/disparity/" + stem + ".pfm";
    MakeParent(disparity);
    WritePfm(disparity, cv::Mat(kRunHeight, kRunWidth, CV_32FC1, cv::Scalar(0.2f)));
    const std::string overlay = dir + "/overlay/" + stem + ".png";
    MakeParent(overlay);
    cv::Mat image(kRunHeight, kRunWidth, CV_8UC3, cv::Scalar(30, 60, 90 + 40 * frame));
    if (!cv::imwrite(overlay, image)) Fail("cannot write " + overlay);
  }
}

std::string ReplaceRunFile(const uint8_t* data, size_t size, RunFiles* files) {
  if (size == 0) return "";
  const std::string content(reinterpret_cast<const char*>(data) + 1, size - 1);
  int which = data[0] % 3;
  if (data[0] == 'f') which = 0;
  if (data[0] == 's') which = 1;
  if (data[0] == 'c') which = 2;
  switch (which) {
    case 0:
      files->frames_jsonl = content;
      return "frames.jsonl";
    case 1:
      files->summary_json = content;
      return "summary.json";
    default:
      files->config_yaml = content;
      return "config.yaml";
  }
}

void WriteFuzzedRunFiles(const uint8_t* data, size_t size, const RunFiles& valid,
                         const std::string& dir) {
  RunFiles files = valid;
  ReplaceRunFile(data, size, &files);
  WriteRunFiles(dir, files);
}

}  // namespace attend::fuzz
