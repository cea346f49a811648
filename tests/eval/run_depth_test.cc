// The targets' depth in `attend compare` and `attend report` (eval/run_depth.h,
// eval/depth_report.h) and the plan view they draw it with (eval/svg_plot.h), on records
// whose depths are set here.
#include "eval/run_depth.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "eval/depth_report.h"
#include "eval/run_comparison.h"
#include "eval/run_report.h"
#include "eval/svg_plot.h"
#include "pipeline/overlay.h"
#include "tests/support/temp_dir.h"

namespace attend {
namespace {

int Count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TargetRecord Seen(int id, double disparity, double disparity_sd) {
  TargetRecord target;
  target.id = id;
  target.bbox = cv::Rect(10 * id, 10, 20, 20);
  target.area = 400;
  target.state = TargetState::kTracked;
  target.disparity_px = disparity;
  target.disparity_sd_px = disparity_sd;
  return target;
}

TargetRecord Placed(int id, cv::Vec3d position, double z_sd) {
  // Disparity 36 / Z, as the lab scene's camera (focal 300 px, baseline 0.12 m) gives.
  TargetRecord target = Seen(id, 36.0 / position[2], 0.5);
  target.has_position = true;
  target.position_m = position;
  target.position_sd_m = cv::Vec3d(0.01, 0.01, z_sd);
  return target;
}

FrameRecord Frame(int index, std::vector<TargetRecord> targets) {
  FrameRecord record;
  record.frame = index;
  record.targets = std::move(targets);
  return record;
}

TEST(RunDepth, SummaryCountsTheSeenTargetsAndAveragesWhatTheyHave) {
  TargetRecord occluded = Placed(3, {0, 0, 9}, 5.0);
  occluded.state = TargetState::kOccluded;  // not seen: left out
  TargetRecord mono = Seen(4, std::nan(""), std::nan(""));
  const std::vector<FrameRecord> frames = {
      Frame(0, {Placed(1, {1, 0, 2}, 0.1), Seen(2, 6.0, 0.3), occluded}),
      Frame(1, {Placed(1, {1, 0, 4}, 0.3), mono})};
  const RunDepth depth = SummariseDepth(frames);
  EXPECT_EQ(depth.target_frames, 4);
  EXPECT_EQ(depth.with_disparity, 3);
  EXPECT_EQ(depth.with_position, 2);
  EXPECT_NEAR(depth.mean_disparity_sd_px, (0.5 + 0.3 + 0.5) / 3, 1e-12);
  EXPECT_NEAR(depth.mean_depth_m, 3.0, 1e-12);
  EXPECT_NEAR(depth.mean_depth_sd_m, 0.2, 1e-12);
  EXPECT_TRUE(depth.any());
  const nlohmann::ordered_json json = RunDepthToJson(depth);
  EXPECT_EQ(json["with_position"], 2);
  EXPECT_NEAR(json["mean_depth_m"].get<double>(), 3.0, 1e-12);

  // A mono run: nothing to show, the means null.
  const RunDepth none = SummariseDepth({Frame(0, {mono})});
  EXPECT_FALSE(none.any());
  EXPECT_TRUE(RunDepthToJson(none)["mean_depth_m"].is_null());
}

TEST(RunDepth, MatchedTargetsDifferByTheirPositionsInTheCommonFrames) {
  // Target 1 of A is target 5 of B. Frame 0: B 0.3 m to the right and 0.4 m further (distance
  // 0.5); frame 1: B's has a disparity only; frame 2: only in A.
  const std::vector<FrameRecord> a = {Frame(0, {Placed(1, {0, 0, 2}, 0.1)}),
                                      Frame(1, {Placed(1, {0, 0, 3}, 0.1)}),
                                      Frame(2, {Placed(1, {0, 0, 4}, 0.1)})};
  const std::vector<FrameRecord> b = {Frame(0, {Placed(5, {0.3, 0, 2.4}, 0.1)}),
                                      Frame(1, {Seen(5, 13.0, 0.2)})};
  const std::optional<DepthComparison> depth = CompareDepth(a, b, {{1, 5}});
  ASSERT_TRUE(depth.has_value());
  ASSERT_EQ(depth->targets.size(), 1u);
  const TargetDepthDifference& t = depth->targets[0];
  EXPECT_EQ(t.id_a, 1);
  EXPECT_EQ(t.id_b, 5);
  EXPECT_EQ(t.position_frames, 1);
  EXPECT_NEAR(t.mean_distance_m, 0.5, 1e-12);
  EXPECT_NEAR(t.mean_depth_difference_m, 0.4, 1e-12);
  // Disparities: frame 0, 36/2.4 - 36/2 = -3; frame 1, 13 - 12 = 1.
  EXPECT_EQ(t.disparity_frames, 2);
  EXPECT_NEAR(t.mean_disparity_difference_px, -1.0, 1e-12);
  EXPECT_NEAR(depth->mean_abs_disparity_difference_px, 2.0, 1e-12);
  EXPECT_NEAR(depth->mean_distance_m, 0.5, 1e-12);
  const nlohmann::ordered_json json = DepthComparisonToJson(depth);
  EXPECT_EQ(json["targets"][0]["b"], 5);
  EXPECT_EQ(json["a"]["with_position"], 3);

  // Runs without any depth: none, written as null.
  const std::vector<FrameRecord> mono = {Frame(0, {Seen(1, std::nan(""), std::nan(""))})};
  EXPECT_FALSE(CompareDepth(mono, mono, {{1, 1}}).has_value());
  EXPECT_TRUE(DepthComparisonToJson(std::nullopt).is_null());
}

TEST(SvgPathPlot, EqualScaleOnBothAxesWithTheCameraAtTheOrigin) {
  EXPECT_DOUBLE_EQ(NiceStep(2.0, 8), 0.5);
  EXPECT_DOUBLE_EQ(NiceStep(10.0, 8), 2.0);
  EXPECT_DOUBLE_EQ(NiceStep(0.7, 7), 0.1);
  PathPlot plot;
  plot.id = "p";
  plot.title = "a <plot>";
  plot.x_min = -1.0, plot.x_max = 1.0, plot.y_min = 0.0, plot.y_max = 1.0;
  plot.origin_label = "camera";
  plot.series = {{"#1 <b>", "rgb(1,2,3)", {0.0, 1.0, std::nan(""), -1.0}, {0.0, 1.0, 0.5, 0.5},
                  {0.2, 0.0, 0.0, 1.0}}};
  const std::string svg = SvgPathPlot(plot);
  // Plot area 58..546 x 32..416: x spans 2 units over 488 px, so a unit is 244 px both ways.
  EXPECT_NE(svg.find("points=\"302.0,416.0 546.0,172.0\""), std::string::npos) << svg;
  EXPECT_NE(svg.find("points=\"58.0,294.0\""), std::string::npos);  // after the break
  EXPECT_EQ(Count(svg, "<polyline"), 2);
  EXPECT_EQ(Count(svg, "<circle"), 2);  // the dots of opacity 0.2 and 1
  EXPECT_NE(svg.find("fill-opacity=\"0.20\""), std::string::npos);
  EXPECT_NE(svg.find("<title>a &lt;plot&gt;</title>"), std::string::npos);
  EXPECT_NE(svg.find(">#1 &lt;b&gt;</text>"), std::string::npos);
  EXPECT_EQ(svg.find("<b>"), std::string::npos);
  EXPECT_NE(svg.find(">camera</text>"), std::string::npos);
  EXPECT_NE(svg.find("clip-path=\"url(#clip-p)\""), std::string::npos);
  // Ticks every 0.5 at multiples of it, with one decimal.
  EXPECT_NE(svg.find(">-1.0</text>"), std::string::npos);
  EXPECT_NE(svg.find(">1.5</text>"), std::string::npos);
}

TEST(TopView, OneLineATargetInItsOverlayColour) {
  std::vector<FrameRecord> frames;
  for (int f = 0; f < 30; ++f) {
    std::vector<TargetRecord> targets = {Placed(2, {-0.5 + 0.02 * f, 0.1, 3.0 - 0.05 * f}, 0.1)};
    // Target 7 is seen in frames 0-9 and 20-29: its line breaks in two.
    if (f < 10 || f >= 20) targets.push_back(Placed(7, {1.0, 0.0, 2.0}, 0.1));
    frames.push_back(Frame(f, targets));
  }
  frames[5].targets.push_back(Seen(9, 4.0, 0.5));  // a disparity but no position: not drawn
  int clipped = -1;
  const std::string svg = TopViewSvg(frames, "Top view: A (<run>)", "tv", 5, &clipped);
  EXPECT_EQ(clipped, 0);
  const cv::Scalar colour = TargetColour(2);
  const std::string css = "rgb(" + std::to_string(static_cast<int>(colour[2])) + "," +
                          std::to_string(static_cast<int>(colour[1])) + "," +
                          std::to_string(static_cast<int>(colour[0])) + ")";
  EXPECT_NE(svg.find("stroke=\"" + css + "\""), std::string::npos);
  EXPECT_EQ(Count(svg, "<polyline"), 3);
  EXPECT_NE(svg.find(">#2</text>"), std::string::npos);
  EXPECT_NE(svg.find(">#7</text>"), std::string::npos);
  EXPECT_EQ(svg.find(">#9</text>"), std::string::npos);
  // Dots at frames 0, 5, ..., 25: 6 for target 2, 4 for target 7 (0, 5, 20, 25); the first at
  // opacity 0.15, the last, frame 25 of 0..29, at 0.15 + 0.85 * 25 / 29.
  EXPECT_EQ(Count(svg, "<circle"), 10);
  EXPECT_NE(svg.find("fill-opacity=\"0.15\""), std::string::npos);
  EXPECT_NE(svg.find("fill-opacity=\"0.88\""), std::string::npos);
  EXPECT_NE(svg.find("Top view: A (&lt;run&gt;)"), std::string::npos);
  EXPECT_NE(svg.find(">Z (m), forward</text>"), std::string::npos);

  // A position far beyond the others is clipped, not allowed to squash the plot.
  for (int f = 0; f < 30; ++f) frames[f].targets[0].position_m[2] = 2.0 + 0.01 * f;
  frames[3].targets[0].position_m[2] = 400.0;
  TopViewSvg(frames, "t", "tv", 0, &clipped);
  EXPECT_EQ(clipped, 1);
  // A non-finite position (made in memory; the reader refuses them) is left out.
  frames[4].targets[0].position_m[0] = std::nan("");
  EXPECT_NE(TopViewSvg(frames, "t", "tv", 0, &clipped), "");
  EXPECT_EQ(TopViewTracks(frames)[0].frames.size(), 29u);
  // No positions: no view.
  EXPECT_EQ(TopViewSvg({Frame(0, {Seen(1, 3.0, 0.1)})}, "t", "tv"), "");
}

TEST(TopView, TheReportShowsTheDepthOnlyForRunsWithOne) {
  testing::TempDir dir;
  RunData a, b, mono;
  a.dir = (dir.path() / "a").string();
  b.dir = (dir.path() / "b&<i>").string();
  mono.dir = (dir.path() / "mono").string();
  for (int f = 0; f < 4; ++f) {
    a.frames.push_back(Frame(f, {Placed(1, {0.1 * f, 0, 2.0}, 0.1)}));
    b.frames.push_back(Frame(f, {Placed(1, {0.1 * f, 0, 2.5}, 0.1)}));
    mono.frames.push_back(Frame(f, {Seen(1, std::nan(""), std::nan(""))}));
  }
  ReportInput input;
  input.runs = {a, b};
  input.comparisons = {CompareRuns(a, b)};
  ASSERT_TRUE(input.comparisons[0].depth.has_value());
  EXPECT_NEAR(input.comparisons[0].depth->mean_distance_m, 0.5, 1e-12);
  EXPECT_TRUE(ComparisonToJson(input.comparisons[0])["depth"].is_object());
  const std::string html = ReportHtml(input);
  EXPECT_NE(html.find("<h2>Depth</h2>"), std::string::npos);
  EXPECT_EQ(Count(html, "<svg"), 2);  // a top view a run
  EXPECT_NE(html.find("Top view: B (b&amp;&lt;i&gt;)"), std::string::npos);
  EXPECT_EQ(html.find("<i>"), std::string::npos);

  input.runs = {mono};
  input.comparisons.clear();
  const std::string plain = ReportHtml(input);
  EXPECT_EQ(plain.find("<h2>Depth</h2>"), std::string::npos);
  EXPECT_EQ(plain.find("<svg"), std::string::npos);
  EXPECT_FALSE(CompareRuns(mono, mono).depth.has_value());
  EXPECT_TRUE(ComparisonToJson(CompareRuns(mono, mono))["depth"].is_null());
}

}  // namespace
}  // namespace attend
