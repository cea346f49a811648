// attend track and attend eval-tracking end to end: tracks.csv of a rectangle moving over a grey
// background, scored against its known boxes; the dumps; the JSON reports; and the exit
// statuses of their errors (SPEC 3.2, 4; docs/TRACKING.md).
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <string>
#include <vector>

#include "io/ground_truth.h"
#include "tests/cli/attend_cli.h"
#include "tests/support/attend_process.h"
#include "tests/support/temp_dir.h"
#include "eval/tracking_scores.h"
#include "io/tracking_files.h"

namespace fs = std::filesystem;

namespace attend {
namespace {

using testing::Attend;
using testing::Contains;
using testing::ReadText;
using testing::Result;
using testing::TempDir;

const cv::Size kSize(160, 120);
const cv::Scalar kRed(40, 40, 210);
const cv::Scalar kBlue(200, 90, 30);
constexpr int kFrames = 24;

// The red rectangle of frame f: 24x18, 2 px right and 1 px down every other frame.
cv::Rect RedBox(int frame) { return {20 + 2 * frame, 40 + frame / 2, 24, 18}; }
// A blue square moving left in the lower half.
cv::Rect BlueBox(int frame) { return {120 - 2 * frame, 80, 20, 20}; }

// A grey background with faint fixed noise, the boxes drawn over it in order.
cv::Mat Frame(int frame, const std::vector<std::pair<cv::Rect, cv::Scalar>>& boxes) {
  cv::Mat image(kSize, CV_8UC3, cv::Scalar(128, 128, 128));
  cv::Mat noise(kSize, CV_8UC3);
  cv::RNG(1000 + frame).fill(noise, cv::RNG::UNIFORM, 0, 6);
  image += noise;
  for (const auto& [box, colour] : boxes) cv::rectangle(image, box, colour, cv::FILLED);
  return image;
}

cv::Mat RedAndBlue(int frame) {
  return Frame(frame, {{RedBox(frame), kRed}, {BlueBox(frame), kBlue}});
}

// Writes frames 0..frames-1 as folder/NNNNNN.png.
template <typename Draw>
void WriteFrames(const std::string& folder, int frames, Draw draw) {
  fs::create_directories(folder);
  for (int f = 0; f < frames; ++f) {
    ASSERT_TRUE(cv::imwrite(folder + "/" + FrameStem(f) + ".png", draw(f)));
  }
}

std::string BoxArgument(const cv::Rect& box) {
  return std::to_string(box.x) + "," + std::to_string(box.y) + "," + std::to_string(box.width) +
         "," + std::to_string(box.height);
}

// The rows of one target, indexed by frame (empty boxes where it has none).
std::vector<cv::Rect2d> BoxesOf(const std::vector<TrackRow>& rows, int id) {
  std::vector<cv::Rect2d> boxes;
  for (const TrackRow& row : rows) {
    if (row.id != id) continue;
    if (row.frame >= static_cast<int>(boxes.size())) boxes.resize(row.frame + 1);
    boxes[row.frame] = row.box;
  }
  return boxes;
}

std::vector<cv::Rect2d> Truth(int frames, cv::Rect (*box)(int)) {
  std::vector<cv::Rect2d> truth;
  for (int f = 0; f < frames; ++f) truth.push_back(cv::Rect2d(box(f)));
  return truth;
}

// An OTB groundtruth_rect.txt of the red box: tab-separated, 1-based.
std::string WriteOtbTruth(const TempDir& dir, int frames) {
  std::string text;
  for (int f = 0; f < frames; ++f) {
    const cv::Rect box = RedBox(f);
    text += std::to_string(box.x + 1) + "\t" + std::to_string(box.y + 1) + "\t" +
            std::to_string(box.width) + "\t" + std::to_string(box.height) + "\n";
  }
  return dir.Write("groundtruth_rect.txt", text);
}

// Every frame with a true box overlaps it by more than `iou` (success at that threshold is 1);
// the failure message lists the frames that do not.
void ExpectEveryFrameAbove(const std::vector<cv::Rect2d>& boxes,
                           const std::vector<cv::Rect2d>& truth, double iou) {
  std::string misses;
  for (size_t f = 0; f < truth.size(); ++f) {
    if (truth[f].empty()) continue;
    const cv::Rect2d box = f < boxes.size() ? boxes[f] : cv::Rect2d();
    const double overlap = ScoreTracking({box}, {truth[f]}).mean_iou;
    if (!(overlap > iou)) {
      misses += " frame " + std::to_string(f) + ": " + std::to_string(box.x) + "," +
                std::to_string(box.y) + "," + std::to_string(box.width) + "," +
                std::to_string(box.height) + " IoU " + std::to_string(overlap) + ";";
    }
  }
  EXPECT_TRUE(misses.empty()) << "IoU <= " << iou << " in" << misses;
}

nlohmann::json LastLineJson(const std::string& text) {
  return nlohmann::json::parse(text.substr(0, text.find('\n')));
}

TEST(TrackCommand, HelpNamesTheOptions) {
  TempDir dir;
  const Result r = Attend(dir, {"track", "--help"});
  EXPECT_EQ(r.status, 0);
  for (const char* flag : {"--sequence", "--images", "--init", "--out", "--set", "--frames",
                           "--dump", "--overwrite"}) {
    EXPECT_TRUE(Contains(r.out, flag)) << flag << "\n" << r.out;
  }
  const Result e = Attend(dir, {"eval-tracking", "--help"});
  EXPECT_EQ(e.status, 0);
  for (const char* flag : {"--gt", "--id", "--gt-id", "--frames"}) {
    EXPECT_TRUE(Contains(e.out, flag)) << flag << "\n" << e.out;
  }
}

TEST(TrackCommand, FollowsAMovingRectangleInAMonocularSequence) {
  TempDir dir;
  WriteFrames(dir.File("seq/left"), kFrames, [](int f) { return Frame(f, {{RedBox(f), kRed}}); });
  const Result r =
      Attend(dir, {"track", "--sequence", "seq", "--init", BoxArgument(RedBox(0)), "--out", "out"});
  ASSERT_EQ(r.status, 0) << r.err;
  // One line of JSON.
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1) << r.out;
  const nlohmann::json summary = LastLineJson(r.out);
  EXPECT_EQ(summary["frames"], kFrames);
  EXPECT_EQ(summary["targets"], 1);
  EXPECT_EQ(summary["first_frame"], 0);
  EXPECT_EQ(summary["last_frame"], kFrames - 1);
  EXPECT_TRUE(summary["lost"].empty());
  EXPECT_GT(summary["ms_per_frame"].get<double>(), 0.0);

  const std::vector<TrackRow> rows = ReadTracksCsv(dir.File("out/tracks.csv"));
  ASSERT_EQ(rows.size(), static_cast<size_t>(kFrames));
  for (int f = 0; f < kFrames; ++f) {
    EXPECT_EQ(rows[f].frame, f);
    EXPECT_EQ(rows[f].id, 1);
    EXPECT_EQ(rows[f].state, "found") << "frame " << f;
  }
  // Every frame overlaps the truth by more than 0.8: success at threshold 0.8 is 1.
  ExpectEveryFrameAbove(BoxesOf(rows, 1), Truth(kFrames, RedBox), 0.8);
  const TrackingScores scores = ScoreTracking(BoxesOf(rows, 1), Truth(kFrames, RedBox));
  EXPECT_EQ(scores.frames, kFrames);
  EXPECT_DOUBLE_EQ(scores.success[16], 1.0);
  EXPECT_DOUBLE_EQ(scores.precision_20, 1.0);
  // No dumps unless asked for.
  EXPECT_FALSE(fs::exists(dir.File("out/masks")));
  EXPECT_FALSE(fs::exists(dir.File("out/overlay")));
}

TEST(TrackCommand, TracksTwoTargetsInAStereoSequenceOverAFrameRange) {
  TempDir dir;
  WriteFrames(dir.File("seq/left"), kFrames, RedAndBlue);
  // The right view is different (and would be a poor match): only the left one is tracked.
  WriteFrames(dir.File("seq/right"), kFrames, [](int f) { return Frame(f, {}); });
  const Result r =
      Attend(dir, {"track", "--sequence", "seq", "--init", BoxArgument(RedBox(4)), "--init",
                   BoxArgument(BlueBox(4)), "--out", "out", "--frames", "4:15"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json summary = LastLineJson(r.out);
  EXPECT_EQ(summary["frames"], 12);
  EXPECT_EQ(summary["targets"], 2);
  EXPECT_EQ(summary["first_frame"], 4);
  EXPECT_EQ(summary["last_frame"], 15);

  const std::vector<TrackRow> rows = ReadTracksCsv(dir.File("out/tracks.csv"));
  ASSERT_EQ(rows.size(), 24u);
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i].frame, 4 + static_cast<int>(i) / 2);
    EXPECT_EQ(rows[i].id, 1 + static_cast<int>(i) % 2);  // ids in order of --init
  }
  std::vector<cv::Rect2d> red = Truth(16, RedBox), blue = Truth(16, BlueBox);
  for (int f = 0; f < 4; ++f) red[f] = blue[f] = cv::Rect2d();
  ExpectEveryFrameAbove(BoxesOf(rows, 1), red, 0.8);
  ExpectEveryFrameAbove(BoxesOf(rows, 2), blue, 0.8);
}

TEST(TrackCommand, ReadsAPlainImageFolderAndDumpsMasksAndOverlays) {
  TempDir dir;
  // OTB names: img/0001.jpg ...; JPEG blurs the edges a little.
  fs::create_directories(dir.File("otb/img"));
  for (int f = 0; f < 12; ++f) {
    char name[16];
    std::snprintf(name, sizeof(name), "%04d.jpg", f + 1);
    ASSERT_TRUE(cv::imwrite(dir.File("otb/img/") + name, Frame(f, {{RedBox(f), kRed}}),
                            {cv::IMWRITE_JPEG_QUALITY, 95}));
  }
  dir.Write("otb/img/notes.txt", "not an image");
  const Result r = Attend(dir, {"track", "--images", "otb/img", "--init", BoxArgument(RedBox(0)),
                                "--out", "out", "--dump", "masks,overlay"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(LastLineJson(r.out)["frames"], 12);
  const std::vector<TrackRow> rows = ReadTracksCsv(dir.File("out/tracks.csv"));
  ASSERT_EQ(rows.size(), 12u);
  // JPEG's 4:2:0 chroma blurs the box's colour edges over 1-2 px, and the tracker leaves that
  // fringe out in some frames: 22x14 of the 24x18 box is IoU 0.71.
  ExpectEveryFrameAbove(BoxesOf(rows, 1), Truth(12, RedBox), 0.65);

  for (int f = 0; f < 12; ++f) {
    const cv::Mat mask =
        cv::imread(dir.File("out/masks/1/" + FrameStem(f) + ".png"), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(mask.empty()) << "frame " << f;
    EXPECT_EQ(mask.type(), CV_8UC1);
    EXPECT_EQ(mask.size(), kSize);
    // The mask covers the box, not the background.
    EXPECT_GT(cv::countNonZero(mask(RedBox(f))), 0.65 * RedBox(f).area()) << "frame " << f;
    EXPECT_LT(cv::countNonZero(mask) - cv::countNonZero(mask(RedBox(f))), 0.2 * RedBox(f).area());
    const cv::Mat overlay = cv::imread(dir.File("out/overlay/" + FrameStem(f) + ".png"));
    ASSERT_FALSE(overlay.empty()) << "frame " << f;
    EXPECT_EQ(overlay.size(), kSize);
  }

  // The OTB folder itself is not a sequence folder; the message says what to do.
  const Result otb =
      Attend(dir, {"track", "--sequence", "otb", "--init", "1,1,5,5", "--out", "out2"});
  EXPECT_EQ(otb.status, 3);
  EXPECT_TRUE(Contains(otb.err, "--images")) << otb.err;
}

TEST(TrackCommand, ReportsAnOccludedTargetAndFindsItAgain) {
  TempDir dir;
  // A blue panel larger than the red box covers it in frames 8..11.
  WriteFrames(dir.File("seq/left"), 18, [](int f) {
    std::vector<std::pair<cv::Rect, cv::Scalar>> boxes = {{RedBox(f), kRed}};
    if (f >= 8 && f <= 11) {
      boxes.push_back(
          {cv::Rect(RedBox(f).tl() - cv::Point(4, 4), RedBox(f).size() + cv::Size(8, 8)), kBlue});
    }
    return Frame(f, boxes);
  });
  const Result r =
      Attend(dir, {"track", "--sequence", "seq", "--init", BoxArgument(RedBox(0)), "--out", "out"});
  ASSERT_EQ(r.status, 0) << r.err;
  const std::vector<TrackRow> rows = ReadTracksCsv(dir.File("out/tracks.csv"));
  ASSERT_EQ(rows.size(), 18u);
  for (const TrackRow& row : rows) {
    const bool hidden = row.frame >= 8 && row.frame <= 11;
    EXPECT_EQ(row.state, hidden ? "occluded" : "found") << "frame " << row.frame;
  }
  // The box of an occluded frame is the last one found.
  EXPECT_EQ(rows[8].box, rows[7].box);
  EXPECT_GT((cv::Rect(rows[17].box) & RedBox(17)).area(), 0.8 * RedBox(17).area());
}

// Every kind follows the rectangle and the summary (printed and OUT/track.json) names it.
TEST(TrackCommand, EveryKindFollowsTheRectangleAndTheSummaryNamesIt) {
  TempDir dir;
  WriteFrames(dir.File("seq/left"), kFrames, [](int f) { return Frame(f, {{RedBox(f), kRed}}); });
  for (const std::string kind : {"bip", "kcf", "csrt"}) {
    const Result r = Attend(dir, {"track", "--sequence", "seq", "--init", BoxArgument(RedBox(0)),
                                  "--out", "out_" + kind, "--set", "tracker.kind=" + kind});
    ASSERT_EQ(r.status, 0) << kind << "\n" << r.err;
    EXPECT_EQ(LastLineJson(r.out)["tracker"], kind);
    const nlohmann::json written =
        nlohmann::json::parse(ReadText(dir.File("out_" + kind + "/track.json")));
    EXPECT_EQ(written["tracker"], kind);
    EXPECT_EQ(written["frames"], kFrames);
    const std::vector<TrackRow> rows = ReadTracksCsv(dir.File("out_" + kind + "/tracks.csv"));
    ASSERT_EQ(rows.size(), static_cast<size_t>(kFrames)) << kind;
    SCOPED_TRACE(kind);
    ExpectEveryFrameAbove(BoxesOf(rows, 1), Truth(kFrames, RedBox), 0.5);
    // The BIP runs as configs/track.yaml says, the correlation mode (which reads no occlusion
    // rules); the other kinds have no mode.
    EXPECT_EQ(written.contains("mode"), kind == "bip");
    EXPECT_FALSE(written.contains("occlusion"));
    if (kind == "bip") EXPECT_EQ(written["mode"], "correlation");
  }
}

TEST(TrackCommand, TheThesisTrackerIsASetAway) {
  TempDir dir;
  WriteFrames(dir.File("seq/left"), 6, [](int f) { return Frame(f, {{RedBox(f), kRed}}); });
  const Result r = Attend(dir, {"track", "--sequence", "seq", "--init", BoxArgument(RedBox(0)),
                                "--out", "out", "--set", "tracker.mode=thesis", "--set",
                                "tracker.occlusion=false"});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json written = nlohmann::json::parse(ReadText(dir.File("out/track.json")));
  EXPECT_EQ(written["mode"], "thesis");
  EXPECT_EQ(written["occlusion"], false);
}

TEST(TrackCommand, SetChangesTheTrackerOptions) {
  TempDir dir;
  WriteFrames(dir.File("seq/left"), 6, [](int f) { return Frame(f, {{RedBox(f), kRed}}); });
  const Result r = Attend(dir, {"track", "--sequence", "seq", "--init", BoxArgument(RedBox(0)),
                                "--out", "out", "--set", "tracker.t_colour=25", "--set",
                                "tracker.min_overlap=0.6", "--set", "tracker.epsilon_max=20"});
  EXPECT_EQ(r.status, 0) << r.err;
}

TEST(TrackCommand, OverwriteReplacesOnlyAPreviousTrackOutput) {
  TempDir dir;
  WriteFrames(dir.File("seq/left"), 4, [](int f) { return Frame(f, {{RedBox(f), kRed}}); });
  const std::vector<std::string> args = {
      "track", "--sequence", "seq",    "--init", BoxArgument(RedBox(0)),
      "--out", "out",        "--dump", "overlay"};
  ASSERT_EQ(Attend(dir, args).status, 0);
  Result r = Attend(dir, args);
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--overwrite")) << r.err;
  dir.Write("out/mine.txt", "kept");
  std::vector<std::string> again = args;
  again.back() = "masks";
  again.push_back("--overwrite");
  r = Attend(dir, again);
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("out/overlay")));
  EXPECT_TRUE(fs::exists(dir.File("out/masks/1/000003.png")));
  EXPECT_EQ(ReadText(dir.File("out/mine.txt")), "kept");
  // A folder that holds something else is not replaced.
  dir.Write("other/file.txt", "x");
  std::vector<std::string> other = args;
  other[6] = "other";
  other.push_back("--overwrite");
  EXPECT_EQ(Attend(dir, other).status, 2);
}

TEST(TrackCommand, UsageAndConfigurationErrorsExitTwo) {
  TempDir dir;
  WriteFrames(dir.File("seq/left"), 3, [](int f) { return Frame(f, {{RedBox(f), kRed}}); });
  const std::string box = BoxArgument(RedBox(0));
  const auto run = [&](const std::vector<std::string>& more) {
    std::vector<std::string> args = {"track"};
    args.insert(args.end(), more.begin(), more.end());
    return Attend(dir, args);
  };
  struct Case {
    std::vector<std::string> args;
    std::vector<std::string> named;  // what the message must name
  };
  const std::vector<Case> cases = {
      {{"--init", box, "--out", "o"}, {"--sequence or --images"}},
      {{"--sequence", "seq", "--images", "seq/left", "--init", box, "--out", "o"}, {"--images"}},
      {{"--sequence", "seq", "--out", "o"}, {"--init"}},
      {{"--sequence", "seq", "--init", box}, {"--out"}},
      {{"--sequence", "seq", "--init", "1,2,3", "--out", "o"}, {"--init 1,2,3", "x,y,w,h"}},
      {{"--sequence", "seq", "--init", "1,2,a,4", "--out", "o"}, {"--init 1,2,a,4"}},
      {{"--sequence", "seq", "--init", "1,2,0,4", "--out", "o"}, {"width and height"}},
      {{"--sequence", "seq", "--init", box, "--out", "o", "--set", "tracker.t_colur=20"},
       {"tracker.t_colur", "t_colour"}},
      {{"--sequence", "seq", "--init", box, "--out", "o", "--set", "segmentation.t_max=20"},
       {"segmentation.t_max", "tracker.KEY"}},
      {{"--sequence", "seq", "--init", box, "--out", "o", "--set", "tracker.alpha=1.5"},
       {"tracker.alpha"}},
      {{"--sequence", "seq", "--init", box, "--out", "o", "--set", "tracker.alpha=abc"},
       {"tracker.alpha"}},
      {{"--sequence", "seq", "--init", box, "--out", "o", "--set", "tracker.epsilon_max=2"},
       {"epsilon_max"}},
      {{"--sequence", "seq", "--init", box, "--out", "o", "--frames", "5"}, {"--frames 5"}},
      {{"--sequence", "seq", "--init", box, "--out", "o", "--frames", "2:1"}, {"--frames 2:1"}},
      {{"--sequence", "seq", "--init", box, "--out", "o", "--dump", "mask"},
       {"mask", "did you mean 'masks'"}},
      {{"--sequence", "seq", "--init", box, "--out", "o", "--bogus"}, {"--bogus"}},
      {{"--sequence", "seq", "--init", box, "--out", "o", "--set", "tracker.kind=kfc"},
       {"tracker.kind", "'kfc'", "did you mean 'kcf'"}},
      {{"--sequence", "seq", "--init", box, "--out", "o", "--set", "tracker.kind=csrt", "--set",
        "tracker.t_colour=25"},
       {"--set tracker.t_colour=25", "tracker.t_colour", "tracker.kind is csrt"}},
      {{"--sequence", "seq", "--init", box, "--out", "o", "--set", "tracker.lost_frames=3"},
       {"tracker.lost_frames", "tracker.kind is bip"}},
  };
  for (const Case& c : cases) {
    const Result r = run(c.args);
    std::string line;
    for (const std::string& arg : c.args) line += arg + " ";
    EXPECT_EQ(r.status, 2) << line << "\n" << r.err;
    for (const std::string& named : c.named) {
      EXPECT_TRUE(Contains(r.err, named)) << line << ": '" << named << "' not in\n" << r.err;
    }
    EXPECT_FALSE(fs::exists(dir.File("o/tracks.csv"))) << line;
  }
  // An output path below a regular file.
  dir.Write("file", "x");
  EXPECT_EQ(run({"--sequence", "seq", "--init", box, "--out", "file/out"}).status, 2);
}

TEST(TrackCommand, BoxesOutsideTheFrameOrEmptyExitTwo) {
  TempDir dir;
  WriteFrames(dir.File("seq/left"), 4, [](int f) { return Frame(f, {{RedBox(f), kRed}}); });
  const std::string good = BoxArgument(RedBox(0));
  const cv::Size size = Frame(0, {}).size();
  const std::string right_edge = std::to_string(size.width - 10) + ",10,20,20";
  for (const std::string kind : {"bip", "kcf"}) {
    for (const std::string& box : {std::string("500,10,20,20"), right_edge,
                                   std::string("-1,10,20,20"), std::string("10,10,0,20")}) {
      const Result r = Attend(dir, {"track", "--sequence", "seq", "--init", good, "--init", box,
                                    "--out", "o", "--set", "tracker.kind=" + kind});
      EXPECT_EQ(r.status, 2) << kind << " " << box << "\n" << r.err;
      EXPECT_TRUE(Contains(r.err, "--init " + box)) << r.err;
      EXPECT_FALSE(fs::exists(dir.File("o/tracks.csv")));
    }
  }
  const Result r = Attend(dir, {"track", "--sequence", "seq", "--init", "500,10,20,20", "--out",
                                "o"});
  EXPECT_TRUE(Contains(r.err, "outside the " + std::to_string(size.width) + "x" +
                                  std::to_string(size.height) + " frame"))
      << r.err;
}

TEST(TrackCommand, BadInputExitsThreeNamingTheBoxOrFrame) {
  TempDir dir;
  WriteFrames(dir.File("seq/left"), 8, [](int f) { return Frame(f, {{RedBox(f), kRed}}); });
  const std::string box = BoxArgument(RedBox(0));

  Result r = Attend(dir, {"track", "--sequence", "missing", "--init", box, "--out", "o"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "missing")) << r.err;
  r = Attend(dir, {"track", "--images", "missing", "--init", box, "--out", "o"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "missing")) << r.err;
  fs::create_directories(dir.File("empty"));
  r = Attend(dir, {"track", "--images", "empty", "--init", box, "--out", "o"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "no images")) << r.err;
  r = Attend(dir, {"track", "--images", "seq/left", "--init", box, "--out", "o", "--frames", "8:"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "8 frames")) << r.err;

  // A box over the plain background after a good one (boxes outside the frame are usage
  // errors, exit 2: BoxesOutsideTheFrameOrEmptyExitTwo).
  r = Attend(dir,
             {"track", "--sequence", "seq", "--init", box, "--init", "100,100,1,1", "--out", "o"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "--init 100,100,1,1 (target 2")) << r.err;
  EXPECT_FALSE(fs::exists(dir.File("o/tracks.csv")));

  // A frame that cannot be decoded: exit 3 naming it; the frames before it are kept.
  {
    std::ofstream corrupt(dir.File("seq/left/000005.png"), std::ios::trunc);
    corrupt << "not a PNG";
  }
  r = Attend(dir, {"track", "--sequence", "seq", "--init", box, "--out", "o"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "frame 5")) << r.err;
  EXPECT_TRUE(Contains(r.err, "000005.png")) << r.err;
  const std::vector<TrackRow> rows = ReadTracksCsv(dir.File("o/tracks.csv"));
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows.back().frame, 4);
  r = Attend(dir, {"track", "--images", "seq/left", "--init", box, "--out", "o2"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "frame 5")) << r.err;
  EXPECT_EQ(ReadTracksCsv(dir.File("o2/tracks.csv")).size(), 5u);

  // A frame of another size in a plain image folder.
  WriteFrames(dir.File("sizes"), 3, [](int f) { return Frame(f, {{RedBox(f), kRed}}); });
  ASSERT_TRUE(cv::imwrite(dir.File("sizes/000002.png"), cv::Mat(60, 80, CV_8UC3, cv::Scalar(0))));
  r = Attend(dir, {"track", "--images", "sizes", "--init", box, "--out", "o3"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "frame 2")) << r.err;
  EXPECT_TRUE(Contains(r.err, "80x60")) << r.err;
}

// ------------------------------------------------------------------------------------------
// attend eval-tracking

TEST(EvalTrackingCommand, ScoresTracksAgainstOtbGroundTruth) {
  TempDir dir;
  // Hand-made tracks: target 1 exact in frames 0..3, shifted by half its width in 4..5;
  // target 2 only in frame 0, then missing.
  std::vector<TrackRow> rows;
  for (int f = 0; f < 6; ++f) {
    cv::Rect2d box(RedBox(f));
    if (f >= 4) box.x += box.width / 2;
    rows.push_back({f, 1, box, f == 5 ? "occluded" : "found"});
  }
  rows.push_back({0, 2, cv::Rect2d(RedBox(0)), "found"});
  WriteTracksCsv(dir.File("tracks.csv"), rows);
  const std::string gt = WriteOtbTruth(dir, 6);

  const Result r = Attend(dir, {"eval-tracking", "tracks.csv", "--gt", gt});
  ASSERT_EQ(r.status, 0) << r.err;
  const nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["gt_format"], "otb");
  EXPECT_TRUE(report["gt_id"].is_null());
  ASSERT_EQ(report["targets"].size(), 2u);
  const nlohmann::json& one = report["targets"][0];
  EXPECT_EQ(one["id"], 1);
  EXPECT_EQ(one["frames"], 6);
  EXPECT_EQ(one["rows"], 6);
  EXPECT_EQ(one["found"], 5);
  EXPECT_EQ(one["first_frame"], 0);
  EXPECT_EQ(one["last_frame"], 5);
  // 4 frames at IoU 1, 2 at IoU 1/3: success 1 up to t = 0.30, 4/6 up to 0.95, 0 at 1.
  EXPECT_NEAR(one["success_auc"].get<double>(), (7.0 + 13.0 * 4.0 / 6.0) / 21.0, 1e-12);
  EXPECT_NEAR(one["mean_iou"].get<double>(), (4.0 + 2.0 / 3.0) / 6.0, 1e-12);
  EXPECT_DOUBLE_EQ(one["precision_20"].get<double>(), 1.0);
  EXPECT_EQ(one["success"].size(), 21u);
  // Target 2 is scored from its first frame to the end of the ground truth: 1 of 6 frames.
  const nlohmann::json& two = report["targets"][1];
  EXPECT_EQ(two["frames"], 6);
  EXPECT_NEAR(two["precision_20"].get<double>(), 1.0 / 6.0, 1e-12);

  // --id and --frames.
  const Result only =
      Attend(dir, {"eval-tracking", "tracks.csv", "--gt", gt, "--id", "1", "--frames", "0:3"});
  ASSERT_EQ(only.status, 0) << only.err;
  const nlohmann::json first = nlohmann::json::parse(only.out)["targets"];
  ASSERT_EQ(first.size(), 1u);
  EXPECT_EQ(first[0]["frames"], 4);
  EXPECT_NEAR(first[0]["success_auc"].get<double>(), 20.0 / 21.0, 1e-12);
}

TEST(EvalTrackingCommand, ScoresAgainstASyntheticObjectsCsv) {
  TempDir dir;
  // Object 3 is the red box, hidden in frame 2; object 4 is elsewhere.
  std::vector<GtObject> objects;
  for (int f = 0; f < 4; ++f) {
    GtObject red;
    red.frame = f;
    red.id = 3;
    red.box = f == 2 ? cv::Rect2d() : cv::Rect2d(RedBox(f));
    red.visible_fraction = f == 2 ? 0.0 : 1.0;
    GtObject other = red;
    other.id = 4;
    other.box = cv::Rect2d(100, 100, 10, 10);
    objects.push_back(red);
    objects.push_back(other);
  }
  fs::create_directories(dir.File("gt"));
  WriteObjectsCsv(dir.File("gt/objects.csv"), objects);
  std::vector<TrackRow> rows;
  for (int f = 0; f < 4; ++f) rows.push_back({f, 1, cv::Rect2d(RedBox(f)), "found"});
  WriteTracksCsv(dir.File("tracks.csv"), rows);

  Result r = Attend(dir, {"eval-tracking", "tracks.csv", "--gt", "gt/objects.csv", "--gt-id", "3"});
  ASSERT_EQ(r.status, 0) << r.err;
  nlohmann::json report = nlohmann::json::parse(r.out);
  EXPECT_EQ(report["gt_format"], "objects.csv");
  EXPECT_EQ(report["gt_id"], 3);
  EXPECT_EQ(report["targets"][0]["frames"], 3);  // the hidden frame is skipped
  EXPECT_NEAR(report["targets"][0]["success_auc"].get<double>(), 20.0 / 21.0, 1e-12);

  r = Attend(dir, {"eval-tracking", "tracks.csv", "--gt", "gt/objects.csv", "--gt-id", "4"});
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(nlohmann::json::parse(r.out)["targets"][0]["success_auc"], 0.0);

  // Which object is meant must be said when there are several.
  r = Attend(dir, {"eval-tracking", "tracks.csv", "--gt", "gt/objects.csv"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--gt-id")) << r.err;
  EXPECT_TRUE(Contains(r.err, "3, 4")) << r.err;
  r = Attend(dir, {"eval-tracking", "tracks.csv", "--gt", "gt/objects.csv", "--gt-id", "9"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--gt-id 9")) << r.err;
}

TEST(EvalTrackingCommand, ErrorsExitTwoOrThree) {
  TempDir dir;
  WriteTracksCsv(dir.File("tracks.csv"), {{0, 1, cv::Rect2d(RedBox(0)), "found"}});
  const std::string gt = WriteOtbTruth(dir, 3);

  Result r = Attend(dir, {"eval-tracking", "tracks.csv"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--gt")) << r.err;
  r = Attend(dir, {"eval-tracking", "tracks.csv", "--gt", gt, "--id", "7"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--id 7")) << r.err;
  r = Attend(dir, {"eval-tracking", "tracks.csv", "--gt", gt, "--gt-id", "1"});
  EXPECT_EQ(r.status, 2);
  EXPECT_TRUE(Contains(r.err, "--gt-id")) << r.err;
  EXPECT_EQ(Attend(dir, {"eval-tracking", "tracks.csv", "--gt", gt, "--frames", "x"}).status, 2);

  r = Attend(dir, {"eval-tracking", "absent.csv", "--gt", gt});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "absent.csv")) << r.err;
  r = Attend(dir, {"eval-tracking", "tracks.csv", "--gt", "absent.txt"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "absent.txt")) << r.err;
  dir.Write("bad.csv", "frame,id,x,y,w,h,state\n0,1,2,3,4,5,found\n1,1,2,3,4,five,found\n");
  r = Attend(dir, {"eval-tracking", "bad.csv", "--gt", gt});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "bad.csv:3")) << r.err;
  dir.Write("bad_gt.txt", "1\t1\t10\t10\n1\t1\t10\n");
  r = Attend(dir, {"eval-tracking", "tracks.csv", "--gt", "bad_gt.txt"});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "bad_gt.txt:2")) << r.err;
  dir.Write("twice.csv", "frame,id,x,y,w,h,state\n0,1,2,3,4,5,found\n0,1,2,3,4,5,found\n");
  r = Attend(dir, {"eval-tracking", "twice.csv", "--gt", gt});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "twice.csv:3: target 1 again in frame 0 (line 2 has it too)"))
      << r.err;
  dir.Write("empty.csv", "frame,id,x,y,w,h,state\n");
  r = Attend(dir, {"eval-tracking", "empty.csv", "--gt", gt});
  EXPECT_EQ(r.status, 3);
  EXPECT_TRUE(Contains(r.err, "no rows")) << r.err;
}

}  // namespace
}  // namespace attend
