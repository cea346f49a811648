// The semi-attentive stage (SPEC 2.4): the whole per-frame pipeline on rendered scenes whose
// ground truth is exact, and the stage alone on drawn frames with chosen saliency maps.
#include "semiattentive/attention.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "colour/colour.h"
#include "eval/run_evaluation.h"
#include "features/builtin.h"
#include "io/skin_files.h"
#include "pipeline/frame_pipeline.h"
#include "synth/renderer.h"
#include "synth/scene.h"
#include "tests/support/temp_dir.h"
#include "util/box.h"

namespace attend {
namespace {

// Runs the pipeline (default configuration without disparity, for speed) over a scene's
// frames; returns the records and the ground truth.
struct SceneRun {
  std::vector<FrameRecord> records;
  std::vector<GtObject> truth;
  std::vector<cv::Mat> inhibited;
};

SceneRun RunScene(const std::string& scene_yaml, int frames, int threads = 1,
                  TrackerKind kind = TrackerKind::kBip) {
  const SceneRenderer renderer(ParseScene(scene_yaml, "test scene"));
  AttendOptions options;
  options.features = ReadFeatureList(
      ParamBlock::Parse("features: [{name: colour_contrast}, {name: intensity_contrast}, "
                        "{name: skin}]",
                        "test.yaml"),
      "features");
  options.threads = threads;
  options.attention.tracker.kind = kind;
  FeatureSetup setup;
  setup.home = testing::ProjectRoot();
  options.attention.skin_model = setup.home + "/configs/skin_tsl.yaml";
  ExecutionContext execution(threads);
  FramePipeline pipeline(options, BuiltinFeatures(), setup, &execution);
  SceneRun run;
  for (int i = 0; i < frames; ++i) {
    const RenderedFrame rendered = renderer.Render(i);
    StereoFrame frame;
    frame.index = i;
    frame.left = rendered.left;
    frame.right = rendered.right;
    FrameRecord record;
    record.frame = i;
    pipeline.Process(frame, &record);
    run.records.push_back(record);
    run.truth.insert(run.truth.end(), rendered.objects.begin(), rendered.objects.end());
    run.inhibited.push_back(pipeline.inhibited().clone());
  }
  return run;
}

const char kHeader[] = R"(
width: 320
height: 240
frames: 60
seed: 3
camera: {focal_px: 300, baseline_m: 0.12}
noise: {left: 1.0, right: 1.0}
background: {depth: 6.0, colour: [130, 130, 130], texture: 10}
objects:
)";

TEST(Attention, ThreeSalientObjectsAreAttendedOnceEach) {
  const std::string scene = std::string(kHeader) + R"(
  - {id: 1, shape: rectangle, size: [0.4, 0.3], colour: [210, 40, 40], path: [{frame: 0, x: 70, y: 70, depth: 3}]}
  - {id: 2, shape: ellipse, size: [0.3, 0.3], colour: [40, 80, 210], path: [{frame: 0, x: 230, y: 80, depth: 3}]}
  - {id: 3, shape: rectangle, size: [0.35, 0.35], colour: [40, 180, 60], path: [{frame: 0, x: 160, y: 180, depth: 3}]}
)";
  const SceneRun run = RunScene(scene, 20);
  const AttentionScores scores = EvaluateAttention(run.records, run.truth);
  EXPECT_EQ(scores.objects, 3);
  EXPECT_EQ(scores.attended, 3);
  for (const ObjectScore& object : scores.per_object) {
    EXPECT_GE(object.first_attended, 0) << "object " << object.id;
    EXPECT_LT(object.first_attended, 5) << "object " << object.id;
  }
  EXPECT_EQ(scores.revisits, 0);
  EXPECT_EQ(scores.identity_switches, 0);
}

// The same scene through the loop with every tracker kind: the records name the kind that
// tracked, each object is attended once and then tracked.
TEST(Attention, EveryTrackerKindRunsTheLoopAndTheRecordsSayWhichTracked) {
  const std::string scene = std::string(kHeader) + R"(
  - {id: 1, shape: rectangle, size: [0.4, 0.3], colour: [210, 40, 40], path: [{frame: 0, x: 70, y: 70, depth: 3}, {frame: 12, x: 100, y: 80, depth: 3}]}
  - {id: 2, shape: ellipse, size: [0.3, 0.3], colour: [40, 80, 210], path: [{frame: 0, x: 230, y: 80, depth: 3}]}
  - {id: 3, shape: rectangle, size: [0.35, 0.35], colour: [40, 180, 60], path: [{frame: 0, x: 160, y: 180, depth: 3}]}
)";
  for (const TrackerKind kind : {TrackerKind::kBip, TrackerKind::kKcf, TrackerKind::kCsrt}) {
    const std::string name = TrackerKindName(kind);
    SCOPED_TRACE(name);
    const SceneRun run = RunScene(scene, 12, 1, kind);
    int tracked = 0, targets = 0;
    for (const FrameRecord& record : run.records) {
      for (const TargetRecord& target : record.targets) {
        ++targets;
        EXPECT_EQ(target.tracker, name) << "frame " << record.frame;
        EXPECT_EQ(target.similarity, kind == TrackerKind::kBip ? "hsv" : "appearance");
        EXPECT_NE(FrameRecordToJson(record).find("\"tracker\":\"" + name + "\""),
                  std::string::npos);
        if (target.state == TargetState::kTracked) ++tracked;
      }
    }
    EXPECT_GE(targets, 20);
    EXPECT_GE(tracked, 15);
    const AttentionScores scores = EvaluateAttention(run.records, run.truth);
    EXPECT_EQ(scores.attended, 3);
    EXPECT_EQ(scores.revisits, 0);
  }
}

TEST(Attention, AnObjectEnteringIsAttendedWithinFiveFrames) {
  const std::string scene = std::string(kHeader) + R"(
  - {id: 1, shape: rectangle, size: [0.4, 0.3], colour: [210, 40, 40], path: [{frame: 0, x: 80, y: 80, depth: 3}]}
  - {id: 2, shape: rectangle, size: [0.4, 0.4], colour: [230, 200, 30], entry: 30,
     path: [{frame: 30, x: 200, y: 150, depth: 3}]}
)";
  const SceneRun run = RunScene(scene, 40);
  const AttentionScores scores = EvaluateAttention(run.records, run.truth);
  ASSERT_EQ(scores.objects, 2);
  const ObjectScore& entering = scores.per_object[1];
  EXPECT_EQ(entering.first_visible, 30);
  EXPECT_GE(entering.first_attended, 30);
  EXPECT_LE(entering.first_attended, 35);
  EXPECT_EQ(scores.revisits, 0);
}

TEST(Attention, AMovingObjectKeepsItsIdentityAndItsInhibition) {
  const std::string scene = std::string(kHeader) + R"(
  - {id: 1, shape: ellipse, size: [0.35, 0.35], colour: [40, 80, 210],
     path: [{frame: 0, x: 60, y: 120, depth: 3}, {frame: 40, x: 260, y: 110, depth: 3}]}
)";
  const SceneRun run = RunScene(scene, 40);
  const AttentionScores scores = EvaluateAttention(run.records, run.truth);
  EXPECT_EQ(scores.attended, 1);
  EXPECT_EQ(scores.identity_switches, 0);
  EXPECT_EQ(scores.revisits, 0);
  int tracked = 0;
  for (size_t f = 0; f < run.records.size(); ++f) {
    for (const TargetRecord& target : run.records[f].targets) {
      EXPECT_EQ(target.id, 1) << "frame " << f;
      if (target.state != TargetState::kTracked) continue;
      ++tracked;
      // The inhibited saliency inside the target's box is near zero: inhibition moves with it.
      EXPECT_LT(cv::mean(run.inhibited[f](target.bbox))[0], 0.02) << "frame " << f;
    }
  }
  EXPECT_GE(tracked, 35);
}

TEST(Attention, TwoThreadsGiveTheSameTargets) {
  const std::string scene = std::string(kHeader) + R"(
  - {id: 1, shape: rectangle, size: [0.4, 0.3], colour: [210, 40, 40], path: [{frame: 0, x: 70, y: 70, depth: 3}, {frame: 15, x: 120, y: 90, depth: 3}]}
  - {id: 2, shape: ellipse, size: [0.3, 0.3], colour: [40, 80, 210], path: [{frame: 0, x: 230, y: 80, depth: 3}]}
)";
  const SceneRun one = RunScene(scene, 15, 1);
  const SceneRun two = RunScene(scene, 15, 2);
  ASSERT_EQ(one.records.size(), two.records.size());
  for (size_t f = 0; f < one.records.size(); ++f) {
    ASSERT_EQ(one.records[f].targets.size(), two.records[f].targets.size()) << "frame " << f;
    for (size_t i = 0; i < one.records[f].targets.size(); ++i) {
      EXPECT_EQ(one.records[f].targets[i].id, two.records[f].targets[i].id);
      EXPECT_EQ(one.records[f].targets[i].bbox, two.records[f].targets[i].bbox);
      EXPECT_EQ(one.records[f].targets[i].state, two.records[f].targets[i].state);
    }
    EXPECT_EQ(cv::norm(one.inhibited[f], two.inhibited[f], cv::NORM_INF), 0.0) << "frame " << f;
  }
  EXPECT_FALSE(one.records.front().targets.empty());
}

// The stage alone, on drawn frames with a drawn saliency map.
struct Drawn {
  cv::Mat bgr, tsl, saliency;
  Segmentation segmentation;
};

Drawn Draw(const std::vector<std::pair<cv::Rect, cv::Scalar>>& boxes,
           const std::vector<cv::Rect>& salient, unsigned seed) {
  Drawn d;
  d.bgr.create(120, 160, CV_8UC3);
  d.bgr.setTo(cv::Scalar(128, 128, 128));
  cv::Mat noise(d.bgr.size(), CV_8UC3);
  cv::RNG(seed).fill(noise, cv::RNG::UNIFORM, 0, 5);
  d.bgr += noise;
  for (const auto& [box, colour] : boxes) d.bgr(box).setTo(colour);
  BgrToTsl(d.bgr, &d.tsl);
  d.saliency = cv::Mat::zeros(d.bgr.size(), CV_32FC1);
  for (const cv::Rect& box : salient) d.saliency(box).setTo(1.f);
  Segmenter segmenter;
  segmenter.Segment(d.bgr, &d.segmentation);
  return d;
}

SkinModel ShippedSkinModel() {
  return LoadSkinModel(testing::ProjectRoot() + "/configs/skin_tsl.yaml");
}

AttentionFrame Step(AttentionStage* stage, const Drawn& d) {
  AttentionFrame frame;
  cv::Mat skin_distance;
  SkinDistanceMap(d.tsl, stage->skin_model(), &skin_distance);
  TrackedTargets tracked;
  stage->Track(d.bgr, skin_distance, &tracked);
  stage->Select(d.bgr, skin_distance, tracked, d.saliency, d.segmentation, &frame);
  return frame;
}

TEST(Attention, ATargetWhoseSaliencyDropsIsReleased) {
  AttentionOptions options;
  options.drop.frames = 4;
  AttentionStage stage(options, ShippedSkinModel());
  const cv::Rect box(60, 40, 30, 24);
  const cv::Scalar red(40, 40, 210);
  AttentionFrame frame = Step(&stage, Draw({{box, red}}, {box}, 0));
  ASSERT_EQ(frame.new_ids, std::vector<int>{1});
  // From frame 1 on the object is no longer salient (the saliency map is empty).
  for (int f = 1; f <= 4; ++f) {
    frame = Step(&stage, Draw({{box, red}}, {}, f));
    ASSERT_EQ(frame.targets.size(), 1u) << "frame " << f;
    EXPECT_EQ(frame.targets[0].state, f < 4 ? TargetState::kTracked : TargetState::kReleased)
        << "frame " << f;
    EXPECT_EQ(frame.targets[0].reason, f < 4 ? ReleaseReason::kNone : ReleaseReason::kLowSaliency)
        << "frame " << f;
  }
  // Released: it inhibits nothing in the frame it is released in, nor after.
  EXPECT_EQ(cv::countNonZero(stage.inhibition()), 0);
  frame = Step(&stage, Draw({{box, red}}, {}, 5));
  EXPECT_TRUE(frame.targets.empty());
}

// A target that shrinks: while its box holds select.min_area pixels it is tracked; the frame
// its box holds fewer it is released as too_small (it can no longer cover its object, which
// would then be selected again while the target is still on it).
TEST(Attention, ATargetWhoseBoxShrinksUnderTheMinimumAreaIsReleased) {
  AttentionOptions options;
  options.select.min_area = 1000;
  // The thesis's tracker follows the fast shrinking; the bounded box follows it by 10 %.
  options.tracker.bip.mode = TrackerMode::kThesis;
  AttentionStage stage(options, ShippedSkinModel());
  const cv::Scalar red(40, 40, 210);
  auto shrunk = [](int f) { return cv::Rect(40, 30, 40 - f, 30 - f); };
  AttentionFrame frame = Step(&stage, Draw({{shrunk(0), red}}, {shrunk(0)}, 0));
  ASSERT_EQ(frame.new_ids, std::vector<int>{1});
  bool released = false;
  for (int f = 1; f <= 6 && !released; ++f) {
    frame = Step(&stage, Draw({{shrunk(f), red}}, {shrunk(f)}, f));
    ASSERT_FALSE(frame.targets.empty()) << "frame " << f;
    const AttendedTarget& target = frame.targets[0];
    ASSERT_EQ(target.id, 1) << "frame " << f;
    const bool small = target.box.area() < 1000;
    EXPECT_EQ(target.state, small ? TargetState::kReleased : TargetState::kTracked)
        << "frame " << f << ", box " << target.box;
    EXPECT_EQ(target.reason, small ? ReleaseReason::kTooSmall : ReleaseReason::kNone)
        << "frame " << f;
    released = small;
  }
  EXPECT_TRUE(released) << "the box never fell under select.min_area";
}

// A target that grows: while its mask is within select.max_area_fraction of the image it is
// tracked and inhibits; the frame its mask passes the fraction it is released as too_large and
// inhibits nothing from then on (the region is then too large to be selected again).
TEST(Attention, ATargetWhoseMaskGrowsPastTheAreaFractionIsReleased) {
  AttentionOptions options;
  options.select.max_area_fraction = 0.2f;  // of 160 x 120: 3840 px
  // The thesis's tracker follows the fast growth; the bounded mode grows 5 % a side a frame.
  options.tracker.bip.mode = TrackerMode::kThesis;
  AttentionStage stage(options, ShippedSkinModel());
  const cv::Scalar red(40, 40, 210);
  auto grown = [](int f) { return cv::Rect(40, 30, 40 + 10 * f, 30 + 8 * f); };
  AttentionFrame frame = Step(&stage, Draw({{grown(0), red}}, {grown(0)}, 0));
  ASSERT_EQ(frame.new_ids, std::vector<int>{1});
  bool released = false;
  for (int f = 1; f <= 6 && !released; ++f) {
    frame = Step(&stage, Draw({{grown(f), red}}, {grown(f)}, f));
    ASSERT_EQ(frame.targets.size(), 1u) << "frame " << f;
    const AttendedTarget& target = frame.targets[0];
    ASSERT_EQ(target.id, 1) << "frame " << f;
    if (target.area > 0.2 * 160 * 120) {
      EXPECT_EQ(target.state, TargetState::kReleased) << "frame " << f << ", area " << target.area;
      EXPECT_EQ(target.reason, ReleaseReason::kTooLarge) << "frame " << f;
      EXPECT_EQ(cv::countNonZero(stage.inhibition()), 0) << "frame " << f;
      released = true;
    } else {
      EXPECT_EQ(target.state, TargetState::kTracked) << "frame " << f << ", area " << target.area;
      EXPECT_GT(cv::countNonZero(stage.inhibition()), target.area * 0.9) << "frame " << f;
    }
  }
  ASSERT_TRUE(released) << "the target never grew past the fraction";
  frame = Step(&stage, Draw({{grown(6), red}}, {grown(6)}, 7));
  EXPECT_TRUE(frame.targets.empty());
  EXPECT_EQ(cv::countNonZero(stage.inhibition()), 0);
}

// With no area limit, a target whose box comes to span the image (>= 0.9 of its width and of
// its height) is released as spans_image.
TEST(Attention, ATargetWhoseBoxSpansTheImageIsReleased) {
  AttentionOptions options;
  options.select.max_area_fraction = 1.f;
  options.drop.frames = 100;  // salient only where it starts: no other target, no drop
  options.select.max_inhibited_fraction = 1.f;
  options.tracker.bip.mode = TrackerMode::kThesis;  // follows the fast growth
  AttentionStage stage(options, ShippedSkinModel());
  const cv::Scalar red(40, 40, 210);
  // 40 x 30 px to 152 x 114 px over frames 0..14, 8 x 6 px a frame (the image is 160 x 120:
  // 144 x 108 spans it).
  auto grown = [](int f) { return cv::Rect(4, 3, 40 + 8 * f, 30 + 6 * f); };
  AttentionFrame frame = Step(&stage, Draw({{grown(0), red}}, {grown(0)}, 0));
  ASSERT_EQ(frame.new_ids, std::vector<int>{1});
  bool released = false;
  for (int f = 1; f <= 14 && !released; ++f) {
    frame = Step(&stage, Draw({{grown(f), red}}, {}, f));
    ASSERT_EQ(frame.targets.size(), 1u) << "frame " << f;
    const AttendedTarget& target = frame.targets[0];
    SCOPED_TRACE("box " + std::to_string(target.box.width) + "x" +
                 std::to_string(target.box.height));
    const bool spans = target.box.width >= 144 && target.box.height >= 108;
    EXPECT_EQ(target.state, spans ? TargetState::kReleased : TargetState::kTracked)
        << "frame " << f;
    EXPECT_EQ(target.reason, spans ? ReleaseReason::kSpansImage : ReleaseReason::kNone)
        << "frame " << f;
    released = spans;
  }
  ASSERT_TRUE(released) << "the target's box never spanned the image";
  EXPECT_EQ(cv::countNonZero(stage.inhibition()), 0);
  frame = Step(&stage, Draw({{grown(14), red}}, {}, 15));
  EXPECT_TRUE(frame.targets.empty());
}

TEST(Attention, AShortOcclusionKeepsTheIdentityAndIsNotReselected) {
  const AttentionOptions options;
  AttentionStage stage(options, ShippedSkinModel());
  const cv::Rect box(60, 40, 30, 24);
  const cv::Scalar red(40, 40, 210), blue(200, 90, 30);
  Step(&stage, Draw({{box, red}}, {box}, 0));
  for (int f = 1; f <= 12; ++f) {
    // Frames 3..7: a blue panel covers the object; the object stays salient when visible.
    const bool hidden = f >= 3 && f <= 7;
    const cv::Rect panel(box.x - 4, box.y - 4, box.width + 8, box.height + 8);
    const Drawn d =
        hidden ? Draw({{box, red}, {panel, blue}}, {}, f) : Draw({{box, red}}, {box}, f);
    const AttentionFrame frame = Step(&stage, d);
    ASSERT_FALSE(frame.targets.empty()) << "frame " << f;
    EXPECT_EQ(frame.targets[0].id, 1) << "frame " << f;
    EXPECT_TRUE(frame.new_ids.empty()) << "frame " << f;
    if (hidden) {
      EXPECT_EQ(frame.targets[0].state, TargetState::kOccluded) << "frame " << f;
    }
    if (f >= 10) {
      EXPECT_EQ(frame.targets[0].state, TargetState::kTracked) << "frame " << f;
    }
  }
}

// While a target is occluded, the area its tracker searches it in (its box and the ROI border
// around it) is inhibited with inhibition.occluded_search: an object that comes out beside the
// box is taken for the occluded target coming back, not attended as a new one. With the box
// alone (false) the same object starts a new target in the frame it appears.
TEST(Attention, AnOccludedTargetInhibitsTheAreaItIsSearchedIn) {
  const cv::Rect box(60, 40, 30, 24);
  const cv::Rect panel(59, 39, 32, 26);   // covers the box and a pixel around it
  const cv::Rect beside(92, 42, 10, 16);  // 2 px right of the box, within the ROI border
  const cv::Scalar red(40, 40, 210), blue(200, 90, 30), green(60, 180, 50);
  for (const bool search : {true, false}) {
    SCOPED_TRACE(search ? "occluded_search" : "box alone");
    AttentionOptions options;
    options.inhibition.occluded_search = search;
    AttentionStage stage(options, ShippedSkinModel());
    ASSERT_EQ(Step(&stage, Draw({{box, red}}, {box}, 0)).new_ids, std::vector<int>{1});
    int started = 0;
    for (int f = 1; f <= 5; ++f) {
      std::vector<std::pair<cv::Rect, cv::Scalar>> drawn = {{box, red}, {panel, blue}};
      std::vector<cv::Rect> salient;
      if (f >= 2) drawn.push_back({beside, green}), salient.push_back(beside);
      const AttentionFrame frame = Step(&stage, Draw(drawn, salient, f));
      ASSERT_FALSE(frame.targets.empty()) << "frame " << f;
      EXPECT_EQ(frame.targets[0].state, TargetState::kOccluded) << "frame " << f;
      started += static_cast<int>(frame.new_ids.size());
      const cv::Point centre(beside.x + beside.width / 2, beside.y + beside.height / 2);
      // (Once started, the new target of the box-alone run inhibits its own mask.)
      if (search || f == 2) {
        EXPECT_EQ(stage.inhibition().at<float>(centre) > 0.f, search) << "frame " << f;
      }
    }
    EXPECT_EQ(started, search ? 0 : 1);
  }
}

TEST(Attention, ASkinObjectIsTrackedWithTheSkinSimilarity) {
  const AttentionOptions options;
  AttentionStage stage(options, ShippedSkinModel());
  const cv::Rect face(70, 30, 26, 34), box(20, 70, 30, 24);
  const cv::Scalar skin(140, 172, 224), green(60, 180, 50);
  AttentionFrame frame = Step(&stage, Draw({{face, skin}, {box, green}}, {face, box}, 0));
  ASSERT_EQ(frame.targets.size(), 2u);
  for (const AttendedTarget& target : frame.targets) {
    const bool on_face = (target.box & face).area() > 0;
    EXPECT_EQ(target.skin, on_face) << target.id;
  }
  frame = Step(&stage, Draw({{face + cv::Point(3, 1), skin}, {box, green}}, {}, 1));
  for (const AttendedTarget& target : frame.targets) EXPECT_EQ(target.state, TargetState::kTracked);
}

// A skin-coloured strip 6 times as long as it is high (a wall's edge, a plank), salient: by
// colour it is skin, by shape it is not a face or a hand. With select.skin_check (the default)
// it starts a colour target; with the thesis's rule, the share alone, a skin target.
TEST(Attention, ASkinColouredStripIsNotASkinTargetUnderTheSkinCheck) {
  const cv::Rect strip(20, 50, 120, 20);
  const cv::Scalar skin(140, 172, 224);
  for (const bool check : {true, false}) {
    AttentionOptions options;
    options.skin_check = check;
    AttentionStage stage(options, ShippedSkinModel());
    const AttentionFrame frame = Step(&stage, Draw({{strip, skin}}, {strip}, 0));
    ASSERT_EQ(frame.targets.size(), 1u) << "check " << check;
    EXPECT_EQ(frame.targets[0].skin, !check) << "check " << check;
  }
}

TEST(Attention, TheRecordsGiveTheInhibitedShareOfTheImage) {
  const std::string scene = std::string(kHeader) + R"(
  - {id: 1, shape: rectangle, size: [0.4, 0.3], colour: [210, 40, 40], path: [{frame: 0, x: 70, y: 70, depth: 3}]}
)";
  const SceneRun run = RunScene(scene, 4);
  ASSERT_EQ(run.records.size(), 4u);
  EXPECT_GE(run.records[0].inhibited_fraction, 0.0);
  // From frame 1 on the red box is tracked and inhibits about its own area and margin.
  for (size_t f = 1; f < run.records.size(); ++f) {
    EXPECT_GT(run.records[f].inhibited_fraction, 0.01) << "frame " << f;
    EXPECT_LT(run.records[f].inhibited_fraction, 0.5) << "frame " << f;
  }
}

// Two salient boxes of 720 px each in a 160 x 120 image (3.75 % each): with
// select.max_inhibited_fraction at 6 % (1152 px) only the first starts, as the second would
// bring the inhibition (the first's 1080 px with its margin, and 720) past it; at 1 (no bound)
// both start.
TEST(Attention, NoNewTargetStartsPastTheInhibitedFraction) {
  const cv::Rect a(20, 30, 30, 24), b(100, 60, 30, 24);
  const cv::Scalar red(40, 40, 210), green(60, 180, 50);
  for (const float bound : {0.06f, 1.f}) {
    AttentionOptions options;
    options.select.max_inhibited_fraction = bound;
    AttentionStage stage(options, ShippedSkinModel());
    Step(&stage, Draw({{a, red}, {b, green}}, {a, b}, 0));
    const AttentionFrame frame = Step(&stage, Draw({{a, red}, {b, green}}, {a, b}, 1));
    EXPECT_EQ(stage.targets_attended(), bound < 1.f ? 1 : 2) << "bound " << bound;
    EXPECT_LE(cv::countNonZero(stage.inhibition()), bound * 160 * 120) << "bound " << bound;
    EXPECT_FALSE(frame.targets.empty());
  }
}

// An object of two colours (a red top on a blue bottom, as a coat on trousers), salient as a
// whole, next to a green object that is not salient. The thesis's seed is the one colour
// region under the candidate; the object seed is both halves, and not the green neighbour.
TEST(Attention, AnObjectSeedTakesEveryColourRegionOfTheSalientObject) {
  const cv::Rect top(50, 30, 30, 24), bottom(50, 54, 30, 30), beside(80, 40, 24, 40);
  const cv::Scalar red(40, 40, 210), blue(200, 70, 40), green(60, 180, 50);
  const Drawn d = Draw({{top, red}, {bottom, blue}, {beside, green}}, {top | bottom}, 0);
  for (const SeedKind kind : {SeedKind::kRegion, SeedKind::kObject}) {
    const std::string seed = SeedKindName(kind);
    AttentionOptions options;
    options.select.seed = kind;
    options.select.max_new = 1;
    AttentionStage stage(options, ShippedSkinModel());
    const AttentionFrame frame = Step(&stage, d);
    ASSERT_EQ(frame.new_ids.size(), 1u) << seed;
    const cv::Rect box = frame.targets[0].box;
    const double iou_top = static_cast<double>((box & top).area()) / (box | top).area();
    const double iou_bottom = static_cast<double>((box & bottom).area()) / (box | bottom).area();
    const double iou_whole =
        static_cast<double>((box & (top | bottom)).area()) / (box | top | bottom).area();
    if (seed == "region") {
      EXPECT_GT(std::max(iou_top, iou_bottom), 0.9) << "box " << box;
      EXPECT_LT(iou_whole, 0.6) << "box " << box;
    } else {
      EXPECT_GT(iou_whole, 0.9) << "box " << box;
      EXPECT_EQ((box & beside).area(), 0) << "box " << box;
    }
  }
}

// The object seed is bounded as a region is: when the salient area's colour regions together
// pass select.max_area_fraction, the target is the one region under the candidate.
TEST(Attention, AnObjectSeedLargerThanTheAreaBoundFallsBackToItsRegion) {
  const cv::Rect top(30, 20, 60, 40), bottom(30, 60, 60, 40);
  const cv::Scalar red(40, 40, 210), blue(200, 70, 40);
  const Drawn d = Draw({{top, red}, {bottom, blue}}, {top | bottom}, 0);
  AttentionOptions options;
  options.select.seed = SeedKind::kObject;
  options.select.max_area_fraction = 0.2f;  // 3840 px: each half fits, both (4800) do not
  options.select.max_inhibited_fraction = 1.f;
  options.select.max_new = 1;
  AttentionStage stage(options, ShippedSkinModel());
  const AttentionFrame frame = Step(&stage, d);
  ASSERT_EQ(frame.new_ids.size(), 1u);
  EXPECT_LE(frame.targets[0].area, 0.2 * 160 * 120);
  EXPECT_LE(frame.targets[0].box.height, 44) << frame.targets[0].box;
}

// Two targets on two red squares; one square slides onto the other and stays there, so both
// trackers end on the same pixels. With the duplicate rule the younger target is released as
// "duplicate" and the older one keeps the object; with drop.max_shared 1 (the thesis's stage)
// both stay on it.
TEST(Attention, ATargetOnAnotherTargetsPixelsIsReleasedAsADuplicate) {
  const cv::Scalar red(40, 40, 210);
  for (const float max_shared : {0.5f, 1.f}) {
    AttentionOptions options;
    options.drop.max_shared = max_shared;
    AttentionStage stage(options, ShippedSkinModel());
    const cv::Rect still(30, 40, 24, 24);
    std::vector<ReleaseReason> reasons;
    int active_at_end = 0;
    for (int f = 0; f <= 30; ++f) {
      const cv::Rect moving(std::max(30, 110 - 4 * f), 40, 24, 24);
      const AttentionFrame frame =
          Step(&stage, Draw({{still, red}, {moving, red}}, {still, moving}, f));
      if (f == 0) {
        ASSERT_EQ(frame.new_ids.size(), 2u);
      }
      active_at_end = 0;
      for (const AttendedTarget& target : frame.targets) {
        if (target.reason != ReleaseReason::kNone) reasons.push_back(target.reason);
        if (target.state == TargetState::kTracked || target.state == TargetState::kOccluded)
          ++active_at_end;
      }
    }
    if (max_shared < 1.f) {
      EXPECT_EQ(reasons, std::vector<ReleaseReason>{ReleaseReason::kDuplicate});
      EXPECT_EQ(active_at_end, 1);
    } else {
      EXPECT_TRUE(reasons.empty()) << reasons.front();
      EXPECT_EQ(active_at_end, 2);
    }
    EXPECT_EQ(stage.targets_attended(), 2) << "max_shared " << max_shared;
  }
}

// Motion grouping (select.group_min_speed): a red-over-blue object moves right 3 px a frame
// under a still green panel that touches its top; only the red half is salient. The
// textures move with their objects and the background's is still, so that the optical flow
// is exact by construction. With grouping the object seed takes the blue half, which moves
// with the red one, and not the green panel, which touches it but stands still; without it
// the target is the red half alone.
TEST(Attention, MotionGroupingJoinsTheRegionsThatMoveWithTheSeedAndNoOthers) {
  const cv::Size size(160, 120);
  cv::Mat background(size, CV_8UC3);
  cv::RNG(11).fill(background, cv::RNG::UNIFORM, 118, 139);
  cv::Mat texture(size, CV_8UC3);
  cv::RNG(12).fill(texture, cv::RNG::UNIFORM, 0, 12);
  const cv::Rect panel(30, 10, 90, 20);
  const auto frame_at = [&](int f, cv::Rect* red_out, cv::Rect* blue_out) {
    const cv::Rect red(40 + 3 * f, 30, 30, 20), blue(40 + 3 * f, 50, 30, 20);
    Drawn d;
    d.bgr = background.clone();
    const auto paint = [&](const cv::Rect& box, const cv::Scalar& colour, int texture_x) {
      d.bgr(box).setTo(colour);
      // The object's own texture, anchored to it.
      d.bgr(box) += texture(cv::Rect(texture_x, box.y, box.width, box.height));
    };
    paint(panel, cv::Scalar(40, 170, 40), panel.x);
    paint(red, cv::Scalar(30, 30, 200), 0);
    paint(blue, cv::Scalar(190, 70, 30), 0);
    BgrToTsl(d.bgr, &d.tsl);
    d.saliency = cv::Mat::zeros(size, CV_32FC1);
    if (f > 0) d.saliency(red).setTo(1.f);
    Segmenter segmenter;
    segmenter.Segment(d.bgr, &d.segmentation);
    *red_out = red, *blue_out = blue;
    return d;
  };
  for (const float speed : {1.f, 0.f}) {
    SCOPED_TRACE(::testing::Message() << "group_min_speed " << speed);
    AttentionOptions options;
    options.select.seed = SeedKind::kObject;
    options.select.group_min_speed = speed;
    options.select.max_new = 1;
    AttentionStage stage(options, ShippedSkinModel());
    cv::Rect red, blue;
    EXPECT_TRUE(Step(&stage, frame_at(0, &red, &blue)).new_ids.empty());
    const AttentionFrame frame = Step(&stage, frame_at(1, &red, &blue));
    ASSERT_EQ(frame.new_ids.size(), 1u);
    const cv::Rect box = frame.targets.back().box;
    const cv::Rect expected = speed > 0.f ? (red | blue) : red;
    EXPECT_GT(BoxIou(box, expected), 0.85) << box << " vs " << expected;
    EXPECT_GE(box.y, panel.br().y - 2) << "the still panel joined: " << box;
  }
}

}  // namespace
}  // namespace attend

namespace attend {
namespace {

// attention.dwell_s: a target found for its dwell (in frames of the sequence's frame rate) is
// released ("dwell") into its object file, which keeps inhibiting it, so that the next salient
// object is attended; with dwell_s 0 it is held while salient (the thesis's rule).
TEST(Attention, ATargetAttendedForItsDwellIsReleasedAndAttentionMovesOn) {
  const cv::Rect first(20, 40, 30, 24), second(100, 40, 30, 24);
  const cv::Scalar red(40, 40, 210), blue(210, 60, 40);
  for (const float dwell_s : {0.f, 0.2f}) {
    AttentionOptions options;
    options.select.max_targets = 1;  // one focus at a time: attention must move on
    options.memory.memory_frames = 50;
    options.memory.dwell_s = dwell_s;
    AttentionStage stage(options, ShippedSkinModel());
    stage.SetFrameRate(10.0);  // 0.2 s: two frames
    std::vector<int> attended;
    std::vector<ReleaseReason> reasons;
    for (int f = 0; f < 8; ++f) {
      const AttentionFrame frame =
          Step(&stage, Draw({{first, red}, {second, blue}}, {first, second}, f));
      for (const AttendedTarget& target : frame.targets) {
        if (target.state == TargetState::kNew) attended.push_back(target.id);
        if (target.state == TargetState::kReleased) reasons.push_back(target.reason);
      }
    }
    SCOPED_TRACE("dwell_s " + std::to_string(dwell_s));
    if (dwell_s == 0.f) {
      EXPECT_EQ(attended, std::vector<int>{1});  // held: the second object is never attended
      EXPECT_TRUE(reasons.empty());
    } else {
      ASSERT_GE(attended.size(), 2u);
      EXPECT_EQ(attended[1], 2);
      ASSERT_FALSE(reasons.empty());
      EXPECT_EQ(reasons[0], ReleaseReason::kDwell);
    }
  }
}

// select.background on a monocular frame: a salient band along the top of the frame (the sky
// of a street scene) is background by the boundary prior and starts nothing, while a salient
// object inside the frame does; with background false (the thesis's stage) the band is
// attended too.
TEST(Attention, ASalientBandAlongTheBorderIsBackground) {
  const cv::Rect band(0, 0, 160, 20), object(60, 60, 30, 24);
  const cv::Scalar sky(230, 200, 160), red(40, 40, 210);
  for (const bool background : {true, false}) {
    AttentionOptions options;
    options.select.background = background;
    options.select.min_area = 50;
    AttentionStage stage(options, ShippedSkinModel());
    const AttentionFrame frame = Step(&stage, Draw({{band, sky}, {object, red}}, {band, object}, 0));
    bool on_band = false, on_object = false;
    for (const AttendedTarget& target : frame.targets) {
      on_band |= (target.box & band).area() > target.box.area() / 2;
      on_object |= (target.box & object).area() > target.box.area() / 2;
    }
    SCOPED_TRACE(background ? "background" : "thesis");
    EXPECT_TRUE(on_object);
    EXPECT_EQ(on_band, !background);
  }
}

}  // namespace
}  // namespace attend
