// attend saliency and attend eval-fixations end to end, on images and fixation datasets built
// here, whose right answers are known by construction (docs/FIXATIONS.md).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/pfm.h"
#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

using testing::Attend;
using testing::ReadText;
using testing::Result;

// A grey image with faint noise and one saturated red square at `object`.
cv::Mat ObjectOnGrey(cv::Size size, const cv::Rect& object, unsigned seed) {
  cv::Mat image(size, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::Mat noise(size, CV_8UC3);
  cv::RNG(seed).fill(noise, cv::RNG::UNIFORM, 0, 6);
  image += noise;
  cv::rectangle(image, object, cv::Scalar(30, 30, 230), cv::FILLED);
  return image;
}

TEST(SaliencyCli, TheSaturatedObjectHasTheHighestSaliencyAtTheImagesOwnSize) {
  testing::TempDir dir;
  // 400 x 300: not the working size, so the map must come back at the image's size.
  const cv::Rect object(250, 60, 60, 50);
  ASSERT_TRUE(cv::imwrite(dir.File("red.png"), ObjectOnGrey({400, 300}, object, 1)));
  const Result r = Attend(dir, {"saliency", "red.png", "--out", "maps", "--features",
                                "--scanpath", "1", "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const cv::Mat map = ReadPfm(dir.File("maps/red.pfm"));
  ASSERT_EQ(map.size(), cv::Size(400, 300));
  double high = 0.0;
  cv::Point at;
  cv::minMaxLoc(map, nullptr, &high, nullptr, &at);
  EXPECT_TRUE(object.contains(at)) << "maximum at " << at;
  // Every pixel of the object (a margin in from its edge, where the upsampling blends) is above
  // every pixel well away from it.
  cv::Mat outside(map.size(), CV_8UC1, cv::Scalar(255));
  outside(cv::Rect(object.x - 20, object.y - 20, object.width + 40, object.height + 40)).setTo(0);
  double object_low = 0.0, background_high = 0.0;
  cv::minMaxLoc(map(cv::Rect(object.x + 3, object.y + 3, object.width - 6, object.height - 6)),
                &object_low);
  cv::minMaxLoc(map, nullptr, &background_high, nullptr, nullptr, outside);
  EXPECT_GT(object_low, background_high);
  EXPECT_TRUE(std::filesystem::exists(dir.File("maps/red.png")));
  EXPECT_TRUE(std::filesystem::exists(dir.File("maps/features/colour_contrast/red.pfm")));
  // The first attended region is the object.
  const nlohmann::json scanpath = nlohmann::json::parse(ReadText(dir.File("maps/scanpath.json")));
  ASSERT_EQ(scanpath["red"].size(), 1u);
  EXPECT_TRUE(object.contains({scanpath["red"][0]["x"].get<int>(), scanpath["red"][0]["y"].get<int>()}));
}

TEST(SaliencyCli, AScanpathStepLandsOnItsTargetsCentreOrOnItsMostSalientPixel) {
  testing::TempDir dir;
  // A long red bar from the image's centre to its right edge; times a narrow centre bias the
  // saliency along the bar is highest at its left end, while its box's centre is 90 px right.
  const cv::Rect bar(200, 130, 180, 40);
  ASSERT_TRUE(cv::imwrite(dir.File("bar.png"), ObjectOnGrey({400, 300}, bar, 3)));
  dir.Write("c.yaml",
            "features:\n  - {name: colour_contrast, weight: 1}\n"
            "  - {name: centre_bias, weight: 1, sigma: 0.15}\n"
            "saliency: {combination: product}\n");
  for (const std::string point : {"centre", "peak"}) {
    const Result r = Attend(dir, {"saliency", "bar.png", "--out", point, "--config", "c.yaml",
                                  "--scanpath", "1", "--scanpath-point", point, "--quiet"});
    ASSERT_EQ(r.status, 0) << r.err;
    const nlohmann::json step =
        nlohmann::json::parse(ReadText(dir.File(point + "/scanpath.json")))["bar"].at(0);
    const std::vector<int> box = step["bbox"];
    ASSERT_EQ(box.size(), 4u);
    // The target is the bar (its colour region), within a pixel of the working size's rounding.
    EXPECT_NEAR(box[0], bar.x, 2);
    EXPECT_NEAR(box[2], bar.width, 3);
    const double x = step["x"], y = step["y"];
    EXPECT_TRUE(cv::Rect(bar.x - 2, bar.y - 2, bar.width + 4, bar.height + 4).contains({int(x), int(y)}))
        << point << " " << x << "," << y;
    if (point == "centre") {
      EXPECT_NEAR(x, bar.x + bar.width / 2.0, 2.0);
    } else {
      EXPECT_LT(x, bar.x + 30) << "the bar's most salient pixel is at its left end";
    }
  }
  // Another word is a bad flag.
  EXPECT_EQ(Attend(dir, {"saliency", "bar.png", "--out", "x", "--scanpath", "1",
                         "--scanpath-point", "middle"}).status, 2);
}

TEST(SaliencyCli, AnImageThatCannotBeDecodedIsNamedAndTheOthersAreDone) {
  testing::TempDir dir;
  ASSERT_TRUE(cv::imwrite(dir.File("good.png"), ObjectOnGrey({160, 120}, {40, 30, 30, 20}, 2)));
  dir.Write("bad.png", "not an image");
  const Result r = Attend(dir, {"saliency", "good.png", "bad.png", "--out", "maps", "--quiet"});
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("bad.png"), std::string::npos) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir.File("maps/good.pfm")));
}

// A dataset of two images whose fixations all lie on a bright square.
void WriteDataset(const testing::TempDir& dir) {
  std::filesystem::create_directories(dir.File("data/stimuli"));
  std::filesystem::create_directories(dir.File("data/fixations"));
  const std::vector<cv::Rect> objects = {{20, 20, 16, 16}, {60, 40, 16, 16}};
  for (size_t i = 0; i < objects.size(); ++i) {
    const std::string id = "im" + std::to_string(i);
    ASSERT_TRUE(cv::imwrite(dir.File("data/stimuli/" + id + ".png"),
                            ObjectOnGrey({100, 80}, objects[i], 3 + i)));
    std::ofstream fixations(dir.File("data/fixations/" + id + ".txt"));
    fixations << "# subject x y (1-based)\n";
    for (int s = 0; s < 3; ++s) {
      fixations << s << " " << objects[i].x + 4 + 3 * s + 1 << " " << objects[i].y + 8 + 1 << "\n";
    }
    // Maps: 1 on the square, 0 elsewhere (a perfect map), and its opposite.
    cv::Mat good(80, 100, CV_32FC1, cv::Scalar(0.f)), bad(80, 100, CV_32FC1, cv::Scalar(1.f));
    good(objects[i]).setTo(1.f);
    bad(objects[i]).setTo(0.f);
    std::filesystem::create_directories(dir.File("good"));
    std::filesystem::create_directories(dir.File("bad"));
    WritePfm(dir.File("good/" + id + ".pfm"), good);
    WritePfm(dir.File("bad/" + id + ".pfm"), bad);
  }
}

TEST(EvalFixationsCli, APerfectMapBeatsItsOppositeAndTheBaselinesAreScored) {
  testing::TempDir dir;
  WriteDataset(dir);
  const Result r = Attend(dir, {"eval-fixations", "good", "bad", "--dataset", "data", "--baselines",
                                "centre", "spectral_residual", "fine_grained", "--out", "scores",
                                "--quiet"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(ReadText(dir.File("scores/fixations.json")));
  const nlohmann::json& methods = report["methods"];
  EXPECT_NEAR(methods["good"]["auc_judd"]["mean"].get<double>(), 1.0, 0.02);
  EXPECT_GT(methods["good"]["nss"]["mean"].get<double>(), 2.0);
  EXPECT_LT(methods["bad"]["nss"]["mean"].get<double>(), 0.0);
  EXPECT_GT(methods["good"]["cc"]["mean"].get<double>(), methods["bad"]["cc"]["mean"].get<double>());
  for (const std::string name : {"centre", "spectral_residual", "fine_grained"}) {
    EXPECT_EQ(methods[name]["images"].get<int>(), 2) << name;
  }
  EXPECT_TRUE(std::filesystem::exists(dir.File("scores/good.csv")));
  EXPECT_NE(r.out.find("| good | 2 |"), std::string::npos) << r.out;
}

TEST(EvalFixationsCli, BadInputNamesTheFileAndLine) {
  testing::TempDir dir;
  WriteDataset(dir);
  {
    std::ofstream bad(dir.File("data/fixations/im1.txt"), std::ios::app);
    bad << "2 oops 7\n";
  }
  Result r = Attend(dir, {"eval-fixations", "good", "--dataset", "data", "--quiet"});
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("im1.txt:5"), std::string::npos) << r.err;
  std::filesystem::remove_all(dir.File("data/fixations"));
  r = Attend(dir, {"eval-fixations", "good", "--dataset", "data", "--quiet"});
  EXPECT_EQ(r.status, 3);
  EXPECT_NE(r.err.find("fixations"), std::string::npos) << r.err;
}

TEST(EvalFixationsCli, AMapOfAnotherSizeIsResizedWithANote) {
  testing::TempDir dir;
  WriteDataset(dir);
  const cv::Mat map = ReadPfm(dir.File("good/im0.pfm"));
  cv::Mat half;
  cv::resize(map, half, {50, 40}, 0, 0, cv::INTER_NEAREST);
  WritePfm(dir.File("good/im0.pfm"), half);
  const Result r = Attend(dir, {"eval-fixations", "good", "--dataset", "data", "--out", "s"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("resized"), std::string::npos) << r.err;
}

TEST(RunCli, WritesTheScanpathInSelectionOrder) {
  testing::TempDir dir;
  // A short still sequence of one image: the object is attended in the first frame.
  std::filesystem::create_directories(dir.File("seq/left"));
  const cv::Rect object(250, 60, 60, 50);
  for (int f = 0; f < 3; ++f) {
    char name[32];
    std::snprintf(name, sizeof(name), "seq/left/%06d.png", f);
    ASSERT_TRUE(cv::imwrite(dir.File(name), ObjectOnGrey({400, 300}, object, 9)));
  }
  const Result r = Attend(dir, {"run", "--sequence", "seq", "--out", "run", "--quiet", "--set",
                                "features.disparity.enabled=false"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json scanpath = nlohmann::json::parse(ReadText(dir.File("run/scanpath.json")));
  ASSERT_FALSE(scanpath.empty());
  EXPECT_EQ(scanpath[0]["frame"], 0);
  // In input pixels (400 x 300, not the 320 x 240 working size): on the object.
  EXPECT_TRUE(object.contains({scanpath[0]["x"].get<int>(), scanpath[0]["y"].get<int>()}))
      << scanpath.dump();
  int previous = -1;
  for (const nlohmann::json& step : scanpath) {
    EXPECT_GE(step["frame"].get<int>(), previous);
    previous = step["frame"].get<int>();
  }
}

TEST(FitWeightsCli, WritesAConfigurationWithTheFittedWeightsThatRuns) {
  testing::TempDir dir;
  WriteDataset(dir);
  dir.Write("two.yaml",
            "features:\n  - {name: colour_contrast, weight: 1}\n  - {name: centre_bias, weight: 1}\n");
  Result r = Attend(dir, {"fit-weights", "--dataset", "data", "--config", "two.yaml", "--train",
                          "2", "--step", "0.5", "--out", "fitted.yaml"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("3 tried"), std::string::npos) << r.out;
  const std::string fitted = ReadText(dir.File("fitted.yaml"));
  EXPECT_NE(fitted.find("--skip 2"), std::string::npos) << fitted;
  // The fitted file is a whole configuration: attend saliency runs with it.
  r = Attend(dir, {"saliency", "data/stimuli", "--out", "maps", "--config", "fitted.yaml",
                   "--quiet"});
  EXPECT_EQ(r.status, 0) << r.err;
}

}  // namespace
}  // namespace attend
