// Object files (semiattentive/object_files.h) and the top-down parts of the stage (detection
// seeds, labels): the files alone, and the stage on drawn frames whose right answer is known
// by construction.
#include "semiattentive/object_files.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>
#include <set>

#include "colour/colour.h"
#include "features/skin.h"
#include "io/skin_files.h"
#include "pyramid/segmentation.h"
#include "semiattentive/attention.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

cv::Mat Frame(const std::vector<std::pair<cv::Rect, cv::Scalar>>& boxes, unsigned seed,
              cv::Size size = {160, 120}) {
  cv::Mat bgr(size, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::Mat noise(bgr.size(), CV_8UC3);
  cv::RNG(seed).fill(noise, cv::RNG::UNIFORM, 0, 5);
  bgr += noise;
  for (const auto& [box, colour] : boxes)
    bgr(box & cv::Rect(0, 0, size.width, size.height)).setTo(colour);
  return bgr;
}

ObjectAppearance AppearanceOf(const cv::Mat& bgr, const cv::Rect& box) {
  return ObjectAppearance::Of(bgr, cv::Mat(), box);
}

TEST(ObjectAppearance, IsSimilarToItselfAndNotToAnotherColour) {
  const cv::Rect box(40, 30, 20, 40);
  const cv::Mat red = Frame({{box, cv::Scalar(40, 40, 210)}}, 1);
  const cv::Mat red_again = Frame({{box, cv::Scalar(40, 40, 210)}}, 2);
  const cv::Mat blue = Frame({{box, cv::Scalar(210, 60, 40)}}, 3);
  EXPECT_GT(AppearanceOf(red, box).Similarity(AppearanceOf(red_again, box)), 0.9);
  EXPECT_LT(AppearanceOf(red, box).Similarity(AppearanceOf(blue, box)), 0.6);
  EXPECT_EQ(ObjectAppearance().Similarity(AppearanceOf(red, box)), 0.0);
}

TEST(ObjectFiles, AFileIsMatchedInsideItsGatesAndForgottenAfterMemoryFrames) {
  ObjectFileOptions options;
  options.memory_frames = 5;
  options.velocity_decay = 1.f;
  ObjectFiles files(options);
  const cv::Rect box(40, 30, 20, 40);
  const cv::Mat red = Frame({{box, cv::Scalar(40, 40, 210)}}, 1);
  ObjectFile file;
  file.id = 7;
  file.box = box;
  file.velocity = {2.f, 0.f};
  file.appearance = AppearanceOf(red, box);
  files.Remember(file);
  files.Age();
  files.Age();  // two frames unseen: predicted 4 px to the right
  EXPECT_EQ(files.files()[0].Predicted(1.f), cv::Rect(44, 30, 20, 40));
  const cv::Rect there(45, 31, 20, 40);
  const cv::Mat seen = Frame({{there, cv::Scalar(40, 40, 210)}}, 2);
  EXPECT_EQ(files.Match(there, AppearanceOf(seen, there), false), 0);
  // Outside the position gate, another size, another look, another kind: no match.
  const cv::Rect far(120, 30, 20, 40);
  const cv::Mat far_frame = Frame({{far, cv::Scalar(40, 40, 210)}}, 3);
  EXPECT_EQ(files.Match(far, AppearanceOf(far_frame, far), false), -1);
  const cv::Rect big(30, 10, 60, 100);
  const cv::Mat big_frame = Frame({{big, cv::Scalar(40, 40, 210)}}, 4);
  EXPECT_EQ(files.Match(big, AppearanceOf(big_frame, big), false), -1);
  const cv::Mat blue = Frame({{there, cv::Scalar(210, 60, 40)}}, 5);
  EXPECT_EQ(files.Match(there, AppearanceOf(blue, there), false), -1);
  EXPECT_EQ(files.Match(there, AppearanceOf(seen, there), true), -1);
  // Its inhibition fades: 1 - absent / (memory_frames + 1) over the predicted box.
  cv::Mat inhibition = cv::Mat::zeros(120, 160, CV_32FC1);
  files.Inhibit(&inhibition);
  EXPECT_FLOAT_EQ(inhibition.at<float>(50, 50), 1.f - 2.f / 6.f);
  EXPECT_FLOAT_EQ(inhibition.at<float>(50, 42), 0.f);
  for (int f = 0; f < 3; ++f) files.Age();
  EXPECT_EQ(files.files().size(), 1u);  // 5 frames unseen: still kept
  files.Age();
  EXPECT_TRUE(files.files().empty());
}

TEST(ObjectFiles, NothingIsRememberedWhenDisabled) {
  ObjectFiles files(ObjectFileOptions{});
  const cv::Rect box(40, 30, 20, 40);
  ObjectFile file;
  file.box = box;
  file.appearance = AppearanceOf(Frame({{box, cv::Scalar(40, 40, 210)}}, 1), box);
  files.Remember(file);
  EXPECT_FALSE(files.enabled());
  EXPECT_TRUE(files.files().empty());
}

// The stage on drawn frames: salient where the drawn objects are.
struct Step {
  cv::Mat bgr, saliency;
};

Step Draw(const std::vector<std::pair<cv::Rect, cv::Scalar>>& boxes,
          const std::vector<cv::Rect>& salient, unsigned seed) {
  Step step;
  step.bgr = Frame(boxes, seed);
  step.saliency = cv::Mat::zeros(step.bgr.size(), CV_32FC1);
  for (const cv::Rect& box : salient) {
    step.saliency(box & cv::Rect(0, 0, step.bgr.cols, step.bgr.rows)).setTo(1.f);
  }
  return step;
}

class Stage {
 public:
  explicit Stage(const AttentionOptions& options)
      : stage_(options, LoadSkinModel(testing::ProjectRoot() + "/configs/skin_tsl.yaml")) {}

  AttentionFrame Run(const Step& step, const std::vector<Detection>& detections = {}) {
    cv::Mat tsl, skin_distance;
    BgrToTsl(step.bgr, &tsl);
    SkinDistanceMap(tsl, stage_.skin_model(), &skin_distance);
    Segmentation segmentation;
    segmenter_.Segment(step.bgr, &segmentation);
    TrackedTargets tracked;
    stage_.Track(step.bgr, skin_distance, &tracked);
    AttentionFrame frame;
    stage_.Select(step.bgr, skin_distance, tracked, step.saliency, segmentation, &frame,
                  detections);
    return frame;
  }
  AttentionStage& stage() { return stage_; }

 private:
  AttentionStage stage_;
  Segmenter segmenter_;
};

const cv::Scalar kRed(40, 40, 210), kBlue(200, 70, 40), kGreen(60, 180, 50);

// An object that leaves the view for longer than its tracker remembers it and comes back
// inside memory_frames resumes its id (state resumed, with the frames it was away); with a
// shorter memory it is a new target.
TEST(ObjectFilesInTheStage, AnObjectThatComesBackWithinMemoryFramesResumesItsId) {
  const cv::Rect box(60, 40, 24, 36);
  constexpr int kAway = 25;  // frames: past the BIP tracker's 1 / alpha = 10
  for (const int memory : {60, 15}) {
    AttentionOptions options;
    options.memory.memory_frames = memory;
    Stage stage(options);
    AttentionFrame frame = stage.Run(Draw({{box, kRed}}, {box}, 0));
    ASSERT_EQ(frame.new_ids, std::vector<int>{1});
    for (int f = 1; f <= 3; ++f) stage.Run(Draw({{box, kRed}}, {box}, f));
    bool lost = false;
    for (int f = 4; f < 4 + kAway; ++f) {
      frame = stage.Run(Draw({}, {}, f));
      for (const AttendedTarget& t : frame.targets) lost |= t.state == TargetState::kLost;
    }
    ASSERT_TRUE(lost) << "the tracker must lose it for the object file to matter";
    frame = stage.Run(Draw({{box, kRed}}, {box}, 100));
    ASSERT_EQ(frame.targets.size(), 1u) << "memory " << memory;
    if (memory == 60) {
      EXPECT_EQ(frame.targets[0].id, 1);
      EXPECT_EQ(frame.targets[0].state, TargetState::kResumed);
      EXPECT_EQ(frame.targets[0].absent_frames, kAway);
      EXPECT_TRUE(frame.new_ids.empty());
      EXPECT_EQ(stage.stage().targets_attended(), 1);
      frame = stage.Run(Draw({{box, kRed}}, {box}, 101));
      ASSERT_EQ(frame.targets.size(), 1u);
      EXPECT_EQ(frame.targets[0].id, 1);
      EXPECT_EQ(frame.targets[0].state, TargetState::kTracked);
    } else {
      EXPECT_EQ(frame.targets[0].id, 2);
      EXPECT_EQ(frame.targets[0].state, TargetState::kNew);
      EXPECT_EQ(frame.new_ids, std::vector<int>{2});
    }
  }
}

// Another object in the same place is not the remembered one: a new id.
TEST(ObjectFilesInTheStage, AnotherLookingObjectInTheSamePlaceIsNew) {
  const cv::Rect box(60, 40, 24, 36);
  AttentionOptions options;
  options.memory.memory_frames = 60;
  Stage stage(options);
  for (int f = 0; f < 4; ++f) stage.Run(Draw({{box, kRed}}, {box}, f));
  for (int f = 4; f < 30; ++f) stage.Run(Draw({}, {}, f));
  const AttentionFrame frame = stage.Run(Draw({{box, kGreen}}, {box}, 100));
  ASSERT_EQ(frame.targets.size(), 1u);
  EXPECT_EQ(frame.targets[0].id, 2);
  EXPECT_EQ(frame.targets[0].state, TargetState::kNew);
}

// Two people-shaped objects (a coat over trousers) walk across each other, the red one in
// front; salient wherever visible. Each keeps its id through the crossing or gets it back
// within a few frames of reappearing, and no third target starts.
TEST(ObjectFilesInTheStage, TwoPeopleWhoCrossKeepTheirIdsAndNoThirdTargetStarts) {
  AttentionOptions options;
  options.memory.memory_frames = 40;
  options.select.seed = SeedKind::kObject;
  options.select.max_new = 1;
  Stage stage(options);
  const cv::Scalar trousers_a(90, 50, 50), trousers_b(40, 110, 110);
  std::set<int> ids;
  std::map<int, int> id_of_person;  // person (0 left-walking red, 1 green) -> last id
  int frames_wrong = 0;
  constexpr int kFrames = 60;
  for (int f = 0; f < kFrames; ++f) {
    // Person 0 walks right from x = 20, person 1 left from x = 116; they overlap around f 24.
    const int x0 = 20 + 2 * f, x1 = 116 - 2 * f;
    const cv::Rect coat0(x0, 30, 18, 26), legs0(x0 + 2, 56, 14, 30);
    const cv::Rect coat1(x1, 34, 18, 26), legs1(x1 + 2, 60, 14, 30);
    // Person 1 is behind: drawn first.
    const Step step =
        Draw({{coat1, kGreen}, {legs1, trousers_b}, {coat0, kRed}, {legs0, trousers_a}},
             {coat1 | legs1, coat0 | legs0}, f);
    const AttentionFrame frame = stage.Run(step);
    for (const AttendedTarget& t : frame.targets) {
      if (!Visible(t.state)) continue;
      ids.insert(t.id);
      const cv::Rect person[2] = {coat0 | legs0, coat1 | legs1};
      const double on0 = static_cast<double>((t.box & person[0]).area()) / t.box.area();
      const double on1 = static_cast<double>((t.box & person[1]).area()) / t.box.area();
      const int person_index = on0 >= on1 ? 0 : 1;
      // Away from the crossing, a target is on the person whose id it first had.
      const bool crossing = std::abs(x0 - x1) < 24;
      if (!crossing) {
        auto known = id_of_person.find(person_index);
        if (known == id_of_person.end()) {
          id_of_person[person_index] = t.id;
        } else if (known->second != t.id) {
          ++frames_wrong;
        }
      }
    }
  }
  EXPECT_LE(ids.size(), 2u) << "a third target started";
  EXPECT_EQ(id_of_person.size(), 2u);
  EXPECT_LE(frames_wrong, 3) << "frames in which a person had another id than before";
}

// A detection box over a two-colour object seeds one target covering both colours, where the
// salient area covers only one of them.
TEST(DetectionSeeds, ADetectionBoxOverATwoColourObjectSeedsOneTargetOnBothColours) {
  const cv::Rect top(50, 30, 30, 24), bottom(50, 54, 30, 30), beside(80, 40, 24, 40);
  const Step step = Draw({{top, kRed}, {bottom, kBlue}, {beside, kGreen}}, {top}, 0);
  const Detection person{top | bottom, "person", 0.9f};
  for (const SeedKind kind : {SeedKind::kObject, SeedKind::kDetection}) {
    const std::string seed = SeedKindName(kind);
    AttentionOptions options;
    options.select.seed = kind;
    options.select.max_new = 1;
    Stage stage(options);
    const AttentionFrame frame = stage.Run(step, {person});
    ASSERT_EQ(frame.new_ids.size(), 1u) << seed;
    const cv::Rect box = frame.targets[0].box;
    const double iou_whole =
        static_cast<double>((box & (top | bottom)).area()) / (box | top | bottom).area();
    if (seed == "detection") {
      EXPECT_GT(iou_whole, 0.9) << "box " << box;
      EXPECT_EQ((box & beside).area(), 0) << "box " << box;
    } else {
      EXPECT_LT(iou_whole, 0.6) << "box " << box;
    }
    // The whole object is labelled by the detection over it; its upper half alone is not
    // (less than select.label_overlap of the detection's box).
    EXPECT_EQ(frame.targets[0].label, seed == "detection" ? "person" : "") << seed;
  }
}

// With detection seeds, the legs of a person whose coat is already a target are part of that
// target, not a new one; without the detection they start one.
TEST(DetectionSeeds, APartOfADetectedObjectAlreadyFollowedStartsNothing) {
  const cv::Rect top(50, 30, 30, 24), bottom(50, 54, 30, 30);
  for (const bool detected : {true, false}) {
    AttentionOptions options;
    options.select.seed = SeedKind::kDetection;
    options.select.max_new = 1;
    Stage stage(options);
    const Detection person{top | bottom, "person", 0.9f};
    std::vector<Detection> detections;
    if (detected) detections.push_back(person);
    AttentionFrame frame = stage.Run(Draw({{top, kRed}, {bottom, kBlue}}, {top}, 0));
    ASSERT_EQ(frame.new_ids.size(), 1u);
    frame = stage.Run(Draw({{top, kRed}, {bottom, kBlue}}, {top, bottom}, 1), detections);
    EXPECT_EQ(frame.new_ids.empty(), detected) << (detected ? "detected" : "not detected");
  }
}

// select.every_detection: a detected object that is not salient starts a target too, after the
// salient one; without it, only the salient one does.
TEST(DetectionSeeds, EveryFreeDetectionStartsATargetWithEveryDetection) {
  const cv::Rect a(20, 20, 24, 30), b(100, 60, 30, 30);
  const std::vector<Detection> people = {{a, "person", 0.9f}, {b, "person", 0.8f}};
  for (const bool every : {true, false}) {
    AttentionOptions options;
    options.select.seed = SeedKind::kDetection;
    options.select.detected_only = true;
    options.select.every_detection = every;
    options.select.max_new = 2;
    Stage stage(options);
    const AttentionFrame frame = stage.Run(Draw({{a, kRed}, {b, kBlue}}, {a}, 0), people);
    ASSERT_EQ(frame.new_ids.size(), every ? 2u : 1u) << every;
    // The salient one first.
    const cv::Rect first = frame.targets[0].box;
    EXPECT_GT((first & a).area(), 0.8 * a.area()) << first;
    if (every) {
      EXPECT_GT((frame.targets[1].box & b).area(), 0.8 * b.area()) << frame.targets[1].box;
      EXPECT_EQ(frame.targets[1].label, "person");
    }
  }
}

// select.detection_box: a recognised target's box is its detection's.
TEST(DetectionSeeds, ARecognisedTargetsBoxIsItsDetectionsWithDetectionBox) {
  const cv::Rect a(40, 30, 24, 40);
  // The detector's box is a little larger than the object (a margin of background).
  const cv::Rect detected(37, 27, 30, 46);
  for (const bool from_detection : {true, false}) {
    AttentionOptions options;
    options.select.seed = SeedKind::kDetection;
    options.select.detection_box = from_detection;
    Stage stage(options);
    stage.Run(Draw({{a, kRed}}, {a}, 0), {{detected, "person", 0.9f}});
    const AttentionFrame frame = stage.Run(Draw({{a, kRed}}, {a}, 1), {{detected, "person", 0.9f}});
    ASSERT_EQ(frame.targets.size(), 1u);
    if (from_detection) {
      EXPECT_EQ(frame.targets[0].box, detected);
    } else {
      EXPECT_NE(frame.targets[0].box, detected);
    }
  }
}

// Where attention looked: the targets' boxes and the candidates weighed, for the gated
// channels of the next frame.
TEST(DetectionSeeds, TheStageSaysWhereAttentionLooked) {
  const cv::Rect a(20, 20, 24, 30), b(100, 60, 30, 30);
  AttentionOptions options;
  options.select.max_new = 1;
  Stage stage(options);
  stage.Run(Draw({{a, kRed}, {b, kBlue}}, {a, b}, 0));
  const std::vector<cv::Rect>& looked = stage.stage().look_regions();
  ASSERT_GE(looked.size(), 2u);
  bool saw_a = false, saw_b = false;
  for (const cv::Rect& box : looked) {
    saw_a |= (box & a).area() >= 0.8 * a.area();
    saw_b |= (box & b).area() >= 0.8 * b.area();
  }
  EXPECT_TRUE(saw_a);
  EXPECT_TRUE(saw_b);  // not a target (max_new 1), but a candidate weighed
}

}  // namespace
}  // namespace attend
