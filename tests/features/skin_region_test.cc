// SkinRegionOptions and JudgeSkinRegion (features/skin.h): regions whose verdict is known by
// construction, then the UCI skin samples and real street frames (skipped without the data).
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <sstream>

#include "colour/colour.h"
#include "features/skin.h"
#include "io/skin_files.h"
#include "pyramid/segmentation.h"
#include "synth/renderer.h"
#include "synth/scene.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

SkinModel Shipped() { return LoadSkinModel(testing::ProjectRoot() + "/configs/skin_tsl.yaml"); }

double SquaredDistanceOf(const SkinModel& model, cv::Vec3b bgr) {
  const cv::Vec2f ts = TslChrominance(bgr[2], bgr[1], bgr[0]);
  return model.SquaredDistance(ts[0], ts[1]);
}

// A colour whose d^2 lies in [low, high) x T_s, found by a scan of a fixed grid.
cv::Vec3b ColourAt(const SkinModel& model, double low, double high) {
  for (int r = 120; r < 256; r += 3) {
    for (int g = 60; g < r; g += 3) {
      for (int b = 40; b < g; b += 3) {
        const cv::Vec3b bgr(b, g, r);
        const double d2 = SquaredDistanceOf(model, bgr) / model.threshold;
        if (d2 >= low && d2 < high) return bgr;
      }
    }
  }
  ADD_FAILURE() << "no colour at d^2 in [" << low << ", " << high << ") T_s";
  return {};
}

struct Frame {
  cv::Mat bgr, tsl;
};

// `shape` (255 on the region) painted in `colour` on a blue wall.
Frame Paint(const cv::Mat& shape, cv::Vec3b colour) {
  Frame frame;
  frame.bgr = cv::Mat(shape.size(), CV_8UC3, cv::Scalar(200, 60, 20));
  frame.bgr.setTo(colour, shape);
  BgrToTsl(frame.bgr, &frame.tsl);
  return frame;
}

cv::Mat Disk(cv::Size size, cv::Point centre, int radius) {
  cv::Mat mask = cv::Mat::zeros(size, CV_8UC1);
  cv::circle(mask, centre, radius, cv::Scalar(255), cv::FILLED);
  return mask;
}

const cv::Size kSize(320, 240);
const cv::Vec3b kSkin(140, 172, 224);

TEST(SkinRegionOptions, DefaultsAreValid) { EXPECT_EQ(SkinRegionOptions().Check(), ""); }

TEST(SkinRegionOptions, CheckNamesTheField) {
  SkinRegionOptions options;
  options.confident = 0.0;
  EXPECT_EQ(options.Check().rfind("confident:", 0), 0u);
  options = SkinRegionOptions();
  options.max_aspect_ratio = 0.5;
  EXPECT_EQ(options.Check().rfind("max_aspect_ratio:", 0), 0u);
  options = SkinRegionOptions();
  options.min_area = 0;
  EXPECT_EQ(options.Check().rfind("min_area:", 0), 0u);
}

TEST(SkinRegion, DistanceMapIsTheSkinMapsDistance) {
  const SkinModel model = Shipped();
  const Frame frame = Paint(Disk(kSize, {100, 100}, 20), kSkin);
  cv::Mat distances, binary;
  SkinDistanceMap(frame.tsl, model, &distances);
  SkinMap(frame.tsl, model, SkinOutput::kBinary, &binary);
  cv::Mat below = distances < model.threshold;
  cv::Mat skin = binary > 0.5f;
  EXPECT_EQ(cv::countNonZero(below != skin), 0);
  EXPECT_NEAR(distances.at<float>(100, 100), SquaredDistanceOf(model, kSkin), 1e-3);
}

// The distance map from the frame a row at a time is the one from its whole TSL image, bit for
// bit, black pixels and saturated colours included (the frame context uses it without the TSL).
TEST(SkinRegion, DistanceMapOfTheFrameIsTheTslImagesBitForBit) {
  const SkinModel model = Shipped();
  cv::Mat bgr(61, 97, CV_8UC3);
  cv::randu(bgr, cv::Scalar::all(0), cv::Scalar::all(256));
  bgr(cv::Rect(0, 0, 10, 5)).setTo(cv::Scalar(0, 0, 0));
  bgr(cv::Rect(20, 7, 9, 4)).setTo(cv::Scalar(255, 255, 255));
  bgr(cv::Rect(40, 9, 6, 6)).setTo(cv::Scalar(0, 0, 255));
  cv::Mat tsl, from_tsl, from_bgr;
  BgrToTsl(bgr, &tsl);
  SkinDistanceMap(tsl, model, &from_tsl);
  SkinDistanceMapOfBgr(bgr, model, &from_bgr);
  ASSERT_EQ(from_bgr.type(), CV_32FC1);
  ASSERT_EQ(from_bgr.size(), bgr.size());
  EXPECT_EQ(std::memcmp(from_tsl.data, from_bgr.data, from_tsl.total() * sizeof(float)), 0);
}

TEST(SkinRegion, ACompactConfidentBlobIsSkin) {
  const SkinModel model = Shipped();
  ASSERT_LT(SquaredDistanceOf(model, kSkin), 0.2 * model.threshold);
  const cv::Mat face = Disk(kSize, {100, 100}, 20);
  const SkinRegionVerdict verdict =
      JudgeSkinRegionTsl(face, Paint(face, kSkin).tsl, model, SkinRegionOptions());
  EXPECT_TRUE(verdict.skin) << verdict.Describe();
  EXPECT_EQ(verdict.area, cv::countNonZero(face));
  EXPECT_GT(verdict.solidity, 0.95);
  EXPECT_NEAR(verdict.aspect_ratio, 1.0, 0.1);
  EXPECT_EQ(verdict.confident_share, 1.0);
}

TEST(SkinRegion, EachBoundRejectsWhatItShould) {
  const SkinModel model = Shipped();
  const SkinRegionOptions options;
  auto judge = [&](const cv::Mat& shape, cv::Vec3b colour) {
    return JudgeSkinRegionTsl(shape, Paint(shape, colour).tsl, model, options);
  };
  // Too large: a wall of skin colour over 39 % of the image.
  cv::Mat wall = cv::Mat::zeros(kSize, CV_8UC1);
  wall(cv::Rect(20, 20, 200, 150)).setTo(255);
  EXPECT_EQ(judge(wall, kSkin).failed, "max_area_fraction");
  // Too small.
  EXPECT_EQ(judge(Disk(kSize, {50, 50}, 2), kSkin).failed, "min_area");
  EXPECT_EQ(judge(cv::Mat::zeros(kSize, CV_8UC1), kSkin).failed, "min_area");
  // Skin by the thesis's threshold (d^2 < T_s) but not confidently: the colour of a wall that
  // grazes the ellipse.
  const cv::Vec3b grazing = ColourAt(model, 0.7, 0.95);
  const cv::Mat blob = Disk(kSize, {100, 100}, 20);
  EXPECT_EQ(judge(blob, grazing).failed, "min_confident_share") << judge(blob, grazing).Describe();
  // Confident in 70 % of the pixels, the rest far from skin: mean distance 0.3 + 0.7 x small.
  {
    Frame frame = Paint(blob, kSkin);
    cv::Mat far = blob.clone();
    far(cv::Rect(0, 0, kSize.width, 100 + 4)).setTo(0);  // the disk's lower part
    frame.bgr.setTo(cv::Scalar(200, 60, 20), far);
    BgrToTsl(frame.bgr, &frame.tsl);
    SkinRegionOptions strict = options;
    strict.max_mean_distance = 0.25;
    const SkinRegionVerdict verdict = JudgeSkinRegionTsl(blob, frame.tsl, model, strict);
    EXPECT_GT(verdict.confident_share, strict.min_confident_share) << verdict.Describe();
    EXPECT_EQ(verdict.failed, "max_mean_distance") << verdict.Describe();
    EXPECT_TRUE(JudgeSkinRegionTsl(blob, frame.tsl, model, options).skin) << verdict.Describe();
  }
  // Irregular: a comb of thin teeth, like grass blades or the mortar-free bricks of a wall.
  cv::Mat comb = cv::Mat::zeros(kSize, CV_8UC1);
  comb(cv::Rect(40, 40, 60, 4)).setTo(255);
  for (int x = 40; x < 100; x += 8) comb(cv::Rect(x, 44, 2, 40)).setTo(255);
  EXPECT_EQ(judge(comb, kSkin).failed, "min_solidity") << judge(comb, kSkin).Describe();
  // Elongated: a bar 8 times as long as wide.
  cv::Mat bar = cv::Mat::zeros(kSize, CV_8UC1);
  bar(cv::Rect(40, 40, 96, 12)).setTo(255);
  EXPECT_EQ(judge(bar, kSkin).failed, "max_aspect_ratio") << judge(bar, kSkin).Describe();
  // The same bar rotated by 45 degrees: the minimum-area rectangle follows it.
  cv::Mat slanted = cv::Mat::zeros(kSize, CV_8UC1);
  cv::line(slanted, {40, 40}, {108, 108}, cv::Scalar(255), 12);
  EXPECT_EQ(judge(slanted, kSkin).failed, "max_aspect_ratio") << judge(slanted, kSkin).Describe();
  // A hand: a palm with four short fingers and a thumb is still compact enough.
  cv::Mat hand = Disk(kSize, {160, 150}, 16);
  for (int i = 0; i < 4; ++i) hand(cv::Rect(146 + 8 * i, 116, 5, 24)).setTo(255);
  cv::line(hand, {145, 155}, {128, 140}, cv::Scalar(255), 6);
  EXPECT_TRUE(judge(hand, kSkin).skin) << judge(hand, kSkin).Describe();
}

TEST(SkinRegion, FaceAndHandOfTheBundledSceneAreSkinRegions) {
  const SkinModel model = Shipped();
  const SceneRenderer renderer(LoadScene(testing::ProjectRoot() + "/sequences/lab.yaml"));
  for (const int index : {1, 10, 40}) {
    const RenderedFrame frame = renderer.Render(index);
    cv::Mat tsl;
    BgrToTsl(frame.left, &tsl);
    for (const int id : {7, 8}) {  // the face and the hand
      const cv::Mat mask = frame.left_ids == id;
      const SkinRegionVerdict verdict = JudgeSkinRegionTsl(mask, tsl, model, SkinRegionOptions());
      EXPECT_TRUE(verdict.skin) << "frame " << index << " object " << id << ": "
                                << verdict.Describe();
    }
    // The red box (id 1) and the shirt (id 6) are not.
    for (const int id : {1, 6}) {
      const SkinRegionVerdict verdict =
          JudgeSkinRegionTsl(frame.left_ids == id, tsl, model, SkinRegionOptions());
      EXPECT_FALSE(verdict.skin) << "frame " << index << " object " << id << ": "
                                 << verdict.Describe();
    }
  }
}

// The reference data folder: $ATTEND_SHARED_DATA, else ../shared/data beside the project.
TEST(SkinRegion, UciSkinSamplesMakeSkinRegionsAndOthersDoNot) {
  const std::string uci = testing::SharedData() + "/skin/Skin_NonSkin.txt";
  if (!fs::exists(uci)) GTEST_SKIP() << uci << " is absent (set ATTEND_SHARED_DATA)";
  const SkinModel model = Shipped();
  const SkinClassifier classifier(model);
  SkinSamples samples;
  ReadSkinText(uci, &samples);
  const SkinRegionOptions options;
  // Pixel rates of "confident skin" against the thesis's threshold.
  auto rate = [&](const std::vector<cv::Vec2f>& set, double bound) {
    int64_t accepted = 0;
    for (const cv::Vec2f& ts : set) accepted += classifier.SquaredDistance(ts[0], ts[1]) < bound;
    return static_cast<double>(accepted) / set.size();
  };
  const double tpr = rate(samples.skin, options.confident * model.threshold);
  const double fpr = rate(samples.nonskin, options.confident * model.threshold);
  std::cout << "confident skin (d^2 < " << options.confident << " T_s): TPR " << tpr << ", FPR "
            << fpr << "; at T_s: TPR " << rate(samples.skin, model.threshold) << ", FPR "
            << rate(samples.nonskin, model.threshold) << "\n";
  EXPECT_GT(tpr, 0.9);
  EXPECT_LT(fpr, 0.012);

  // Disks of 400 samples drawn at random from one class, written into the TSL image directly.
  const cv::Mat disk = Disk(cv::Size(80, 80), {40, 40}, 11);
  std::mt19937 random(7);
  int skin_passed = 0, nonskin_passed = 0;
  constexpr int kTrials = 200;
  for (int trial = 0; trial < kTrials; ++trial) {
    for (const bool skin : {true, false}) {
      const std::vector<cv::Vec2f>& set = skin ? samples.skin : samples.nonskin;
      std::uniform_int_distribution<size_t> pick(0, set.size() - 1);
      cv::Mat tsl(disk.size(), CV_32FC3, cv::Scalar(0, 0, 0));
      for (int y = 0; y < tsl.rows; ++y) {
        for (int x = 0; x < tsl.cols; ++x) {
          const cv::Vec2f ts = set[pick(random)];
          tsl.at<cv::Vec3f>(y, x) = cv::Vec3f(ts[0], ts[1], 128.f);
        }
      }
      const bool passed = JudgeSkinRegionTsl(disk, tsl, model, options).skin;
      (skin ? skin_passed : nonskin_passed) += passed;
    }
  }
  std::cout << "random UCI disks passing: skin " << skin_passed << "/" << kTrials << ", non-skin "
            << nonskin_passed << "/" << kTrials << "\n";
  EXPECT_EQ(skin_passed, kTrials);
  EXPECT_EQ(nonskin_passed, 0);
}

// The people's boxes of each frame of a MOT sequence in attend layout (gt/objects.csv).
std::map<int, std::vector<cv::Rect>> ReadPeople(const std::string& csv) {
  std::map<int, std::vector<cv::Rect>> people;
  std::ifstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    std::stringstream fields(line);
    std::string f[6];
    for (std::string& field : f) std::getline(fields, field, ',');
    people[std::stoi(f[0])].push_back(cv::Rect(cv::Point(std::stod(f[2]), std::stod(f[3])),
                                               cv::Size(std::stod(f[4]), std::stod(f[5]))));
  }
  return people;
}

TEST(SkinRegion, OnStreetFramesOnlyRegionsOnPeoplePass) {
  const std::string root = testing::SharedData() + "/mot";
  if (!fs::exists(root + "/TUD-Campus/gt/objects.csv")) {
    GTEST_SKIP() << root << " is absent (set ATTEND_SHARED_DATA)";
  }
  const SkinModel model = Shipped();
  const SkinRegionOptions options;
  Segmenter segmenter;  // the defaults of configs/default.yaml's segmentation
  Segmentation segmentation;
  for (const std::string sequence : {"TUD-Campus", "TUD-Stadtmitte"}) {
    int old_rule = 0, old_rule_off_people = 0, passed = 0, passed_off_people = 0;
    std::map<std::string, int> failures;
    const auto people = ReadPeople(root + "/" + sequence + "/gt/objects.csv");
    for (int index = 0; index < 180; index += 10) {
      char name[32];
      std::snprintf(name, sizeof(name), "/left/%06d.jpg", index);
      const cv::Mat full = cv::imread(root + "/" + sequence + name, cv::IMREAD_COLOR);
      if (full.empty()) break;
      // At the working size of configs/default.yaml (320 x 240), as the attention stage sees it.
      cv::Mat bgr, tsl, distances, skin;
      cv::resize(full, bgr, cv::Size(320, 240), 0, 0, cv::INTER_AREA);
      const double scale = 320.0 / full.cols;
      BgrToTsl(bgr, &tsl);
      SkinDistanceMap(tsl, model, &distances);
      skin = distances < model.threshold;
      cv::Mat on_people = cv::Mat::zeros(bgr.size(), CV_8UC1);
      if (people.count(index)) {
        for (const cv::Rect& box : people.at(index)) {
          const cv::Rect scaled(cv::Point(box.x * scale, box.y * scale),
                                cv::Size(box.width * scale, box.height * scale));
          on_people(scaled & cv::Rect(0, 0, bgr.cols, bgr.rows)).setTo(255);
        }
      }
      segmenter.Segment(bgr, &segmentation);
      for (size_t r = 0; r < segmentation.regions.size(); ++r) {
        const int area = segmentation.regions[r].area;
        if (area < 120) continue;  // select.min_area
        const cv::Mat mask = segmentation.labels == static_cast<int>(r);
        // The attention stage's current rule: half of the region's pixels skin.
        if (cv::countNonZero(skin & mask) < 0.5 * area) continue;
        const bool off_people = cv::countNonZero(on_people & mask) < 0.5 * area;
        ++old_rule;
        old_rule_off_people += off_people;
        const SkinRegionVerdict verdict = JudgeSkinRegion(mask, distances, model.threshold, options);
        if (verdict.skin) {
          ++passed;
          passed_off_people += off_people;
          if (off_people && sequence == "TUD-Campus") {
            ADD_FAILURE() << sequence << " frame " << index << ": " << verdict.Describe()
                          << " at " << cv::boundingRect(mask);
          }
        } else {
          ++failures[verdict.failed];
        }
      }
    }
    std::cout << sequence << ": skin regions by the 50 % rule " << old_rule << " ("
              << old_rule_off_people << " off people); confident skin-shaped " << passed << " ("
              << passed_off_people << " off people); failed:";
    for (const auto& [bound, count] : failures) std::cout << " " << bound << " " << count;
    std::cout << "\n";
    // The old rule does take background (the reason for this test).
    EXPECT_GT(old_rule_off_people, 0) << sequence;
    if (sequence == "TUD-Campus") {
      // Gravel, the building's panels, the hedge: none passes.
      EXPECT_EQ(passed_off_people, 0);
    } else {
      // The shop windows of TUD-Stadtmitte are lit warm: their chrominance is skin's and their
      // panes are compact, so many pass (docs/SKIN.md, "Skin regions": an open problem). This
      // bounds the share measured at the commit that added the test (220 of 538).
      EXPECT_LT(passed_off_people, 0.45 * old_rule_off_people);
    }
  }
}

}  // namespace
}  // namespace attend
