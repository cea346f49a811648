#include "io/skin_files.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <system_error>
#include <utility>

#include "colour/colour.h"
#include "config/param_block.h"
#include "config/read_fields.h"
#include "io/image_file.h"
#include "util/error.h"
#include "util/file_checks.h"
#include "util/output_folder.h"
#include "util/strings.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

std::string Quoted(const std::string& text) {
  YAML::Emitter out;
  out << YAML::DoubleQuoted << text;
  return out.c_str();
}

// What the rule in a model file means, for the file's comments.
std::string ExplainRule(const std::string& rule) {
  if (rule == "youden") return "youden: Youden's J, it maximises TPR - FPR on the training split";
  if (rule.rfind("tpr:", 0) == 0) {
    return rule + ": the smallest threshold accepting at least " + rule.substr(4) +
           " of the training skin samples";
  }
  return rule.empty() ? "not recorded" : rule;
}

// The keys of a model file: the model's, then its `training:` block's.
const OptionFields<SkinModel>& ModelFields() {
  static const OptionFields<SkinModel> fields = {
      {"mean",
       NumbersMember<SkinModel>{
           [](const SkinModel& m) { return std::vector<double>{m.mean.x(), m.mean.y()}; },
           [](SkinModel* m, const std::vector<double>& v) { m->mean = Eigen::Vector2d(v[0], v[1]); }, 2},
       Range::Any(), "the mean TSL chrominance (T, S) of skin"},
      {"covariance",
       NumbersMember<SkinModel>{
           [](const SkinModel& m) {
             const Eigen::Matrix2d& c = m.covariance;
             return std::vector<double>{c(0, 0), c(0, 1), c(1, 0), c(1, 1)};
           },
           [](SkinModel* m, const std::vector<double>& v) {
             m->covariance << v[0], v[1], v[2], v[3];
           },
           4},
       Range::Any(), "its covariance, row by row"},
      {"threshold", &SkinModel::threshold, Range::Any(),
       "T_s: skin where the squared Mahalanobis distance is below this"}};
  return fields;
}

const OptionFields<SkinModel::Provenance>& ProvenanceFields() {
  using P = SkinModel::Provenance;
  const Range rate = Range::Closed(0.0, 1.0);
  static const OptionFields<P> fields = {
      {"command", &P::command, "the skin-train invocation"},
      {"data", &P::data, "the training data as given to skin-train"},
      {"rule", &P::rule, "how the threshold was chosen"},
      {"skin_samples", &P::skin_samples, Range::Any(), "skin samples of the training split"},
      {"nonskin_samples", &P::nonskin_samples, Range::Any(), "other samples of it"},
      {"holdout_fraction", &P::holdout_fraction, Range{0.0, 1.0, false, true},
       "the share held out"},
      {"seed", &P::seed, Range::Any(), "the split's seed"},
      {"training_tpr", &P::training_tpr, rate, "true positive rate on the training split"},
      {"training_fpr", &P::training_fpr, rate, "false positive rate on it"},
      {"holdout_tpr", &P::holdout_tpr, rate, "true positive rate on the held-out split"},
      {"holdout_fpr", &P::holdout_fpr, rate, "false positive rate on it"}};
  return fields;
}

// One line of text for a message: at most 60 characters, unprintable bytes shown as '?'.
std::string Excerpt(const char* begin, const char* end) {
  std::string text(begin, std::min<size_t>(end - begin, 60));
  for (char& c : text) {
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  }
  if (end - begin > 60) text += "...";
  return text;
}

bool IsBlank(char c) { return c == ' ' || c == '\t'; }

}  // namespace

SkinModel LoadSkinModel(const std::string& path) {
  const ParamBlock block = ParamBlock::LoadFile(path);
  SkinModel model;
  ReadFields(block, ModelFields(), &model);
  ReadSection(block, "training", ProvenanceFields(), &model.provenance);
  block.CheckNoUnknownKeys();

  for (const char* key : {"mean", "covariance", "threshold"}) {
    if (!block.Has(key)) block.Fail(key, "required key is missing");
  }
  const SkinModelProblem problem = FindSkinModelProblem(model);
  if (!problem.key.empty()) block.Fail(problem.key, problem.message);
  return model;
}

void SaveSkinModel(const SkinModel& model, const std::string& path) {
  const std::string problem = model.Check();
  ATTEND_CHECK(problem.empty()) << "saving an invalid skin model: " << problem;
  const SkinModel::Provenance& p = model.provenance;
  const Eigen::Matrix2d& c = model.covariance;

  std::ostringstream text;
  text << "# attend skin colour model (SPEC 2.3, thesis 5.1.1, docs/SKIN.md): a Gaussian over the\n"
          "# TSL chrominance x = (T, S) of skin pixels, T in [0, 1), S in [0, 255]. A pixel is\n"
          "# skin iff (x - mean)^T covariance^-1 (x - mean) < threshold.\n"
       << "mean: [" << ShortestNumber(model.mean[0]) << ", " << ShortestNumber(model.mean[1])
       << "]\n"
       << "# Row-major 2x2: [var T, cov(T, S), cov(T, S), var S].\n"
       << "covariance: [" << ShortestNumber(c(0, 0)) << ", " << ShortestNumber(c(0, 1)) << ", "
       << ShortestNumber(c(1, 0)) << ", " << ShortestNumber(c(1, 1)) << "]\n"
       << "# T_s on the squared Mahalanobis distance, chosen by the rule training.rule:\n"
       << "# " << ExplainRule(p.rule) << ".\n"
       << "threshold: " << ShortestNumber(model.threshold) << "\n"
       << "# How the model was made; informative only. Sample counts and training rates are of\n"
          "# the training split; held-out rates of the samples that the split set aside.\n"
       << "training:\n"
       << "  command: " << Quoted(p.command) << "\n"
       << "  data: " << Quoted(p.data) << "\n"
       << "  rule: " << Quoted(p.rule) << "\n"
       << "  holdout_fraction: " << ShortestNumber(p.holdout_fraction) << "\n"
       << "  seed: " << p.seed << "\n"
       << "  skin_samples: " << p.skin_samples << "\n"
       << "  nonskin_samples: " << p.nonskin_samples << "\n";
  const std::pair<const char*, double> rates[] = {{"training_tpr", p.training_tpr},
                                                  {"training_fpr", p.training_fpr},
                                                  {"holdout_tpr", p.holdout_tpr},
                                                  {"holdout_fpr", p.holdout_fpr}};
  for (const auto& [key, value] : rates) {
    if (value >= 0.0) text << "  " << key << ": " << ShortestNumber(value) << "\n";
  }

  // Written beside the target and renamed over it: a reader sees the old file or the new one.
  ReplaceFile(path, "the model file", [&](const std::string& temporary) {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << text.str();
    file.close();
    return static_cast<bool>(file);
  });
}

void ReadSkinText(const std::string& path, SkinSamples* samples) {
  ReadSkinText(path, [samples](const cv::Vec2f& ts, bool skin) {
    (skin ? samples->skin : samples->nonskin).push_back(ts);
  });
}

void ReadSkinText(const std::string& path, const SkinSampleSink& sink) {
  RequireRegularFile(path, "the skin samples", ExitStatus::kBadInput, kMaxTextBytes);
  std::ifstream file(path, std::ios::binary);
  if (!file) throw InputError(path + ": cannot read the file (missing or not readable)");
  // The whole file at once, parsed in place: the UCI file (3 MB) reads in a few milliseconds.
  const std::string text((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  if (file.bad()) throw InputError(path + ": read error");

  const char* p = text.data();
  const char* const end = text.data() + text.size();
  int64_t line = 0;
  int64_t samples = 0;
  while (p < end) {
    ++line;
    const char* const line_begin = p;
    const char* line_end = static_cast<const char*>(memchr(p, '\n', end - p));
    if (line_end == nullptr) line_end = end;
    const char* content_end = line_end;
    if (content_end > line_begin && content_end[-1] == '\r') --content_end;
    p = line_end + 1;

    const char* q = line_begin;
    while (q < content_end && IsBlank(*q)) ++q;
    if (q == content_end) continue;  // a blank line

    int values[4];
    bool ok = true;
    for (int i = 0; i < 4 && ok; ++i) {
      if (i > 0) {
        const char* const before = q;
        while (q < content_end && IsBlank(*q)) ++q;
        ok = q > before;
      }
      const auto [next, status] = std::from_chars(q, content_end, values[i]);
      ok = ok && status == std::errc() && (next == content_end || IsBlank(*next));
      q = next;
    }
    while (ok && q < content_end && IsBlank(*q)) ++q;
    ok = ok && q == content_end;
    for (int i = 0; i < 3 && ok; ++i) ok = values[i] >= 0 && values[i] <= 255;
    ok = ok && (values[3] == 1 || values[3] == 2);
    if (!ok) {
      throw InputError(path + ":" + std::to_string(line) +
                       ": expected 'B G R label' (B, G, R in 0..255; label 1 skin, 2 not skin), "
                       "got '" +
                       Excerpt(line_begin, content_end) +
                       "' (an image with its mask is given as IMAGE:MASK)");
    }
    // The file holds B G R; TSL takes R, G, B.
    sink(TslChrominance(values[2], values[1], values[0]), values[3] == 1);
    ++samples;
  }
  if (samples == 0) throw InputError(path + ": holds no samples ('B G R label' lines)");
}

void ReadSkinImagePair(const std::string& image_path, const std::string& mask_path,
                       SkinSamples* samples) {
  ReadSkinImagePair(image_path, mask_path, [samples](const cv::Vec2f& ts, bool skin) {
    (skin ? samples->skin : samples->nonskin).push_back(ts);
  });
}

void ReadSkinImagePair(const std::string& image_path, const std::string& mask_path,
                       const SkinSampleSink& sink) {
  // IMREAD_COLOR gives 8-bit BGR whatever the file holds. The mask is read as grey at its own
  // depth, so that a 16-bit mask with small values is not scaled to zero.
  const cv::Mat bgr = ReadNamedImageFile(image_path, cv::IMREAD_COLOR, "image");
  const cv::Mat mask =
      ReadNamedImageFile(mask_path, cv::IMREAD_GRAYSCALE | cv::IMREAD_ANYDEPTH, "mask");
  if (mask.size() != bgr.size()) {
    throw InputError(mask_path + ": the mask is " + std::to_string(mask.cols) + "x" +
                     std::to_string(mask.rows) + " but its image " + image_path + " is " +
                     std::to_string(bgr.cols) + "x" + std::to_string(bgr.rows));
  }
  cv::Mat skin;
  cv::compare(mask, 0, skin, cv::CMP_NE);
  cv::Mat tsl;
  BgrToTsl(bgr, &tsl);
  for (int row = 0; row < tsl.rows; ++row) {
    const cv::Vec3f* pixel = tsl.ptr<cv::Vec3f>(row);
    const uchar* label = skin.ptr<uchar>(row);
    for (int col = 0; col < tsl.cols; ++col) {
      sink(cv::Vec2f(pixel[col][0], pixel[col][1]), label[col] != 0);
    }
  }
}

namespace {

// The regular, non-hidden files of a folder by stem. Two files with one stem are ambiguous.
std::map<std::string, fs::path> FilesByStem(const fs::path& folder, const std::string& item) {
  std::map<std::string, fs::path> files;
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    if (name.empty() || name[0] == '.' || !entry.is_regular_file(error)) continue;
    const std::string stem = entry.path().stem().string();
    const auto [it, inserted] = files.emplace(stem, entry.path());
    if (!inserted) {
      throw InputError(item + ": " + it->second.string() + " and " + entry.path().string() +
                       " have the same stem '" + stem + "'; cannot tell which one to pair");
    }
  }
  if (error)
    throw InputError(folder.string() + ": cannot list the folder (" + error.message() + ")");
  return files;
}

// A folder with images/ and masks/: every image with the mask of the same stem, in order of
// the stems.
void ReadSkinFolder(const std::string& item, const SkinSampleSink& sink) {
  const fs::path images_folder = fs::path(item) / "images";
  const fs::path masks_folder = fs::path(item) / "masks";
  std::error_code error;
  if (!fs::is_directory(images_folder, error) || !fs::is_directory(masks_folder, error)) {
    throw InputError(item + ": a data folder needs the subfolders images/ and masks/");
  }
  const std::map<std::string, fs::path> images = FilesByStem(images_folder, item);
  const std::map<std::string, fs::path> masks = FilesByStem(masks_folder, item);
  if (images.empty()) throw InputError(images_folder.string() + ": holds no images");
  for (const auto& [stem, image] : images) {
    if (masks.count(stem) == 0) {
      throw InputError(image.string() + ": no mask with the stem '" + stem + "' in " +
                       masks_folder.string());
    }
  }
  for (const auto& [stem, mask] : masks) {
    if (images.count(stem) == 0) {
      throw InputError(mask.string() + ": no image with the stem '" + stem + "' in " +
                       images_folder.string());
    }
  }
  for (const auto& [stem, image] : images) {
    ReadSkinImagePair(image.string(), masks.at(stem).string(), sink);
  }
}

}  // namespace

void ReadSkinData(const std::string& item, const SkinSampleSink& sink) {
  std::error_code error;
  if (fs::is_directory(item, error)) return ReadSkinFolder(item, sink);
  if (fs::exists(item, error)) return ReadSkinText(item, sink);
  const size_t first_colon = item.find(':');
  if (first_colon == std::string::npos) throw InputError(item + ": no such file or folder");
  // Paths may hold colons themselves: split at the first colon that leaves an existing image.
  size_t colon = first_colon;
  for (size_t at = first_colon; at != std::string::npos; at = item.find(':', at + 1)) {
    if (fs::exists(item.substr(0, at), error)) {
      colon = at;
      break;
    }
  }
  ReadSkinImagePair(item.substr(0, colon), item.substr(colon + 1), sink);
}

}  // namespace attend
