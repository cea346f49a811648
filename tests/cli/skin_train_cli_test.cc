// attend skin-train end to end: the data formats, the model file and report it writes, the
// reproducible split, and the exit statuses of its errors (SPEC 3.2, docs/SKIN.md).
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <sstream>

#include "io/skin_files.h"
#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;
using testing::TempDir;

// `skin` rows of skin tones (R > G > B, in the proportions of faces) and `nonskin` rows of
// blues and greens, interleaved, as `B G R label` text. Fixed seed.
std::string SkinText(int skin, int nonskin, uint32_t seed = 5) {
  std::mt19937 random(seed);
  std::uniform_int_distribution<int> red(150, 240), noise(-8, 8), any(0, 255);
  std::ostringstream text;
  for (int i = 0; i < std::max(skin, nonskin); ++i) {
    if (i < skin) {
      const int r = red(random);
      text << std::clamp(r * 55 / 100 + noise(random), 0, 255) << " "
           << std::clamp(r * 72 / 100 + noise(random), 0, 255) << " " << r << " 1\n";
    }
    if (i < nonskin) {
      const int low = any(random) / 3, high = 128 + any(random) / 2;
      if (i % 2 == 0) {
        text << high << " " << any(random) / 2 << " " << low << "\t2\n";  // blue
      } else {
        text << low << " " << high << " " << low << "\t2\n";  // green
      }
    }
  }
  return text.str();
}

// An image with a noisy skin-coloured ellipse on a noisy blue background, and its mask.
void WriteImagePair(const std::string& image_path, const std::string& mask_path, int seed) {
  cv::Mat image(48, 64, CV_8UC3, cv::Scalar(190, 100, 50));
  cv::Mat mask(48, 64, CV_8UC1, cv::Scalar(0));
  const cv::Point centre(20 + 3 * seed, 24);
  cv::ellipse(image, centre, cv::Size(14, 18), 0, 0, 360, cv::Scalar(110, 150, 210), cv::FILLED);
  cv::ellipse(mask, centre, cv::Size(14, 18), 0, 0, 360, cv::Scalar(255), cv::FILLED);
  cv::Mat noise(image.size(), CV_8UC3);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::UNIFORM, 0, 12);
  image += noise;
  ASSERT_TRUE(cv::imwrite(image_path, image));
  ASSERT_TRUE(cv::imwrite(mask_path, mask));
}

nlohmann::json ParseReport(const Result& r) {
  EXPECT_EQ(r.status, 0) << r.err;
  return nlohmann::json::parse(r.out);
}

TEST(SkinTrainCommand, HelpDocumentsTheDataFormatsAndRules) {
  TempDir dir;
  const Result r = Attend(dir, {"skin-train", "--help"});
  EXPECT_EQ(r.status, 0);
  for (const char* part : {"B G R label", "IMAGE:MASK", "images/", "masks/", "youden", "tpr:X",
                           "--holdout", "--seed", "--overwrite", "docs/SKIN.md"}) {
    EXPECT_TRUE(Contains(r.out, part)) << part << "\n" << r.out;
  }
}

TEST(SkinTrainCommand, TrainsOnTextAndWritesTheModelAndAReport) {
  TempDir dir;
  const std::string data = dir.Write("data.txt", SkinText(600, 900));
  const std::string model_path = dir.File("models/skin.yaml");
  const nlohmann::json report = ParseReport(Attend(dir, {"skin-train", data, "--out", model_path}));

  EXPECT_EQ(report["samples"]["skin"], 600);
  EXPECT_EQ(report["samples"]["nonskin"], 900);
  EXPECT_EQ(report["rule"], "youden");
  EXPECT_EQ(report["seed"], 1);
  EXPECT_EQ(report["holdout_fraction"], 0.2);
  const int holdout =
      report["holdout"]["skin"].get<int>() + report["holdout"]["nonskin"].get<int>();
  const int train = report["train"]["skin"].get<int>() + report["train"]["nonskin"].get<int>();
  EXPECT_EQ(holdout + train, 1500);
  EXPECT_NEAR(holdout, 300, 60);
  // Skin tones and blues or greens are far apart in TSL.
  EXPECT_GT(report["holdout"]["tpr"].get<double>(), 0.97);
  EXPECT_LT(report["holdout"]["fpr"].get<double>(), 0.02);

  const SkinModel model = LoadSkinModel(model_path);
  EXPECT_EQ(model.threshold, report["threshold"].get<double>());
  EXPECT_EQ(model.mean[0], report["mean"][0].get<double>());
  EXPECT_EQ(model.covariance(1, 1), report["covariance"][3].get<double>());
  EXPECT_EQ(model.provenance.holdout_tpr, report["holdout"]["tpr"].get<double>());
  EXPECT_EQ(model.provenance.holdout_fpr, report["holdout"]["fpr"].get<double>());
  EXPECT_EQ(model.provenance.skin_samples, report["train"]["skin"].get<int64_t>());
  EXPECT_EQ(model.provenance.data, data);
  EXPECT_TRUE(Contains(model.provenance.command, "attend skin-train " + data))
      << model.provenance.command;
  // Skin tones are near T = 0.5 (r' > 0, g' slightly below 0).
  EXPECT_NEAR(model.mean[0], 0.52, 0.05);
}

TEST(SkinTrainCommand, TheSplitIsReproducibleAndFollowsTheSeed) {
  TempDir dir;
  const std::string data = dir.Write("data.txt", SkinText(300, 300));
  const Result first = Attend(dir, {"skin-train", data, "--out", dir.File("a.yaml")});
  const Result second = Attend(dir, {"skin-train", data, "--out", dir.File("b.yaml")});
  const nlohmann::json a = ParseReport(first), b = ParseReport(second);
  EXPECT_EQ(a["threshold"], b["threshold"]);
  EXPECT_EQ(a["holdout"], b["holdout"]);
  EXPECT_EQ(a["covariance"], b["covariance"]);

  const nlohmann::json other =
      ParseReport(Attend(dir, {"skin-train", data, "--out", dir.File("c.yaml"), "--seed", "2"}));
  EXPECT_NE(other["train"]["skin"], a["train"]["skin"]);  // another split
  const nlohmann::json none =
      ParseReport(Attend(dir, {"skin-train", data, "--out", dir.File("d.yaml"), "--holdout", "0"}));
  EXPECT_EQ(none["train"]["skin"], 300);
  EXPECT_TRUE(none["holdout"]["tpr"].is_null());
  EXPECT_EQ(LoadSkinModel(dir.File("d.yaml")).provenance.holdout_tpr, -1.0);
}

TEST(SkinTrainCommand, TprRuleReachesItsTargetOnTheTrainingSplit) {
  TempDir dir;
  const std::string data = dir.Write("data.txt", SkinText(400, 100));
  const nlohmann::json report = ParseReport(
      Attend(dir, {"skin-train", data, "--out", dir.File("m.yaml"), "--rule", "tpr:0.9"}));
  EXPECT_EQ(report["rule"], "tpr:0.9");
  EXPECT_GE(report["train"]["tpr"].get<double>(), 0.9);
  EXPECT_LT(report["train"]["tpr"].get<double>(), 0.91);
}

TEST(SkinTrainCommand, TrainsOnImageMaskPairsAndFolders) {
  TempDir dir;
  fs::create_directories(dir.path() / "set" / "images");
  fs::create_directories(dir.path() / "set" / "masks");
  WriteImagePair(dir.File("set/images/a.png"), dir.File("set/masks/a.png"), 1);
  WriteImagePair(dir.File("set/images/b.jpg"), dir.File("set/masks/b.png"), 2);
  const int skin_a =
      cv::countNonZero(cv::imread(dir.File("set/masks/a.png"), cv::IMREAD_GRAYSCALE));
  const int skin_b =
      cv::countNonZero(cv::imread(dir.File("set/masks/b.png"), cv::IMREAD_GRAYSCALE));

  const nlohmann::json folder =
      ParseReport(Attend(dir, {"skin-train", dir.File("set"), "--out", dir.File("f.yaml")}));
  EXPECT_EQ(folder["samples"]["skin"], skin_a + skin_b);
  EXPECT_EQ(folder["samples"]["nonskin"], 2 * 48 * 64 - skin_a - skin_b);
  EXPECT_GT(folder["holdout"]["tpr"].get<double>(), 0.97);
  EXPECT_LT(folder["holdout"]["fpr"].get<double>(), 0.02);

  // The same two pairs given one by one, in the folder's order (by stem): the same samples in
  // the same order, so the same split and model.
  const nlohmann::json pairs = ParseReport(
      Attend(dir, {"skin-train", dir.File("set/images/a.png") + ":" + dir.File("set/masks/a.png"),
                   dir.File("set/images/b.jpg") + ":" + dir.File("set/masks/b.png"), "--out",
                   dir.File("p.yaml")}));
  EXPECT_EQ(pairs["samples"], folder["samples"]);
  EXPECT_EQ(pairs["threshold"], folder["threshold"]);
  EXPECT_EQ(pairs["holdout"], folder["holdout"]);

  // Text and images mix.
  const std::string text = dir.Write("more.txt", SkinText(50, 50));
  const nlohmann::json mixed =
      ParseReport(Attend(dir, {"skin-train", text, dir.File("set"), "--out", dir.File("m.yaml")}));
  EXPECT_EQ(mixed["samples"]["skin"], skin_a + skin_b + 50);
}

// Runs skin-train and checks its exit status, that stderr names `named`, and that nothing was
// written: not the model, not its folder, not a temporary file.
void ExpectFailure(const TempDir& dir, std::vector<std::string> args, int status,
                   const std::string& named) {
  args.insert(args.begin(), "skin-train");
  args.push_back("--out");
  args.push_back(dir.File("out/model.yaml"));
  const Result r = Attend(dir, args);
  EXPECT_EQ(r.status, status) << r.err;
  EXPECT_TRUE(Contains(r.err, "attend: error: ")) << r.err;
  EXPECT_TRUE(Contains(r.err, named)) << "expected '" << named << "' in: " << r.err;
  EXPECT_FALSE(fs::exists(dir.File("out")));
}

TEST(SkinTrainCommand, BadDataIsExitStatus3NamingFileAndLine) {
  TempDir dir;
  const std::string good = dir.Write("good.txt", SkinText(50, 50));
  const std::string bad = dir.Write("bad.txt", "10 20 30 1\n10 20 30 1\n40 50 300 2\n");
  ExpectFailure(dir, {good, bad}, 3, "bad.txt:3: expected 'B G R label'");
  ExpectFailure(dir, {dir.File("absent.txt")}, 3, "absent.txt: no such file or folder");
  const std::string nonskin = dir.Write("nonskin.txt", "10 20 30 2\n40 50 60 2\n");
  ExpectFailure(dir, {nonskin}, 3, "no skin samples");
  ExpectFailure(dir, {dir.File("absent.png") + ":" + dir.File("mask.png")}, 3, "absent.png");

  fs::create_directories(dir.path() / "set" / "images");
  fs::create_directories(dir.path() / "set" / "masks");
  WriteImagePair(dir.File("set/images/a.png"), dir.File("set/masks/a.png"), 1);
  WriteImagePair(dir.File("set/images/b.png"), dir.File("other.png"), 2);
  ExpectFailure(dir, {dir.File("set")}, 3, "b.png: no mask with the stem 'b'");
  ExpectFailure(dir, {dir.path().string()}, 3, "needs the subfolders images/ and masks/");
  cv::imwrite(dir.File("small.png"), cv::Mat(10, 10, CV_8UC1, cv::Scalar(255)));
  ExpectFailure(dir, {dir.File("set/images/a.png") + ":" + dir.File("small.png")}, 3,
                "small.png: the mask is 10x10");
}

TEST(SkinTrainCommand, BadFlagsAreExitStatus2) {
  TempDir dir;
  const std::string data = dir.Write("data.txt", SkinText(50, 50));
  ExpectFailure(dir, {data, "--rule", "best"}, 2, "threshold rule 'best'");
  ExpectFailure(dir, {data, "--holdout", "1"}, 2, "--holdout");
  ExpectFailure(dir, {data, "--seed", "-1"}, 2, "--seed");
  ExpectFailure(dir, {data, "--colour"}, 2, "--colour");
  const Result missing_out = Attend(dir, {"skin-train", data});
  EXPECT_EQ(missing_out.status, 2);
  EXPECT_TRUE(Contains(missing_out.err, "--out")) << missing_out.err;
}

TEST(SkinTrainCommand, AnExistingModelIsReplacedOnlyWithOverwrite) {
  TempDir dir;
  const std::string data = dir.Write("data.txt", SkinText(50, 50));
  const std::string model = dir.Write("model.yaml", "old\n");
  Result r = Attend(dir, {"skin-train", data, "--out", model});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "model.yaml: already exists (pass --overwrite")) << r.err;
  EXPECT_EQ(ReadText(model), "old\n");
  r = Attend(dir, {"skin-train", data, "--out", model, "--overwrite"});
  EXPECT_EQ(r.status, 0) << r.err;
  EXPECT_GT(LoadSkinModel(model).threshold, 0.0);
  // Only the model: no temporary file is left beside it.
  int entries = 0;
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    entries += entry.path().filename().string().rfind(".model.yaml", 0) == 0 ? 100 : 1;
  }
  EXPECT_EQ(entries, 4);  // data.txt, model.yaml, stdout, stderr
  // A folder is not a model file.
  fs::create_directories(dir.path() / "folder");
  r = Attend(dir, {"skin-train", data, "--out", dir.File("folder"), "--overwrite"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "is a folder")) << r.err;
}

}  // namespace
}  // namespace attend
