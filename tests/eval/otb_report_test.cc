// The OTB report from results made by hand (eval/otb_results.h, eval/otb_report.h,
// eval/svg_plot.h): mean curves per group, the summary, the page's plots and legends.
#include "eval/otb_report.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "eval/otb_results.h"
#include "eval/svg_plot.h"

namespace attend {
namespace {

// How often `needle` occurs in `text`.
int Count(const std::string& text, const std::string& needle) {
  int count = 0;
  for (size_t at = text.find(needle); at != std::string::npos; at = text.find(needle, at + 1)) {
    ++count;
  }
  return count;
}

// A run whose success curve is `success` at every threshold below 1 and whose precision curve
// is `precision` from 5 px on.
OtbRun Run(double success, double precision, double ms) {
  OtbRun run;
  run.started = true;
  run.scores.success.assign(21, success);
  run.scores.success[20] = 0.0;
  run.scores.precision.assign(51, 0.0);
  std::fill(run.scores.precision.begin() + 5, run.scores.precision.end(), precision);
  run.scores.success_auc = success * 20.0 / 21.0;
  run.scores.precision_20 = precision;
  run.ms_per_frame = ms;
  run.updates = 9;
  return run;
}

// Three sequences, two trackers; "far" has SV and OCC, "near" SV, "plain" none.
OtbResults Results() {
  OtbResults results;
  results.trackers = {{"slow", "csrt-like", {}}, {"csrt", "csrt", {}}};
  results.sequences = {
      {"far", "f", "f/g", 10, 64, 48, {"SV", "OCC"}, {Run(0.2, 0.3, 8.0), Run(0.8, 0.9, 4.0)}},
      {"near", "n", "n/g", 10, 64, 48, {"SV"}, {Run(0.6, 1.0, 2.0), Run(0.4, 0.5, 4.0)}},
      {"plain", "p", "p/g", 10, 64, 48, {}, {Run(1.0, 1.0, 1.0), Run(1.0, 1.0, 2.0)}}};
  results.command_line = "attend eval-tracking --otb DIR --out REPORT";
  return results;
}

TEST(OtbResults, GroupsAverageTheSequencesCurves) {
  const std::vector<OtbGroup> groups = OtbGroups(Results());
  // All sequences, then the attributes in the benchmark's order: SV before OCC.
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0].title, "All sequences");
  EXPECT_EQ(groups[1].code, "SV");
  EXPECT_EQ(groups[1].title, "Scale Variation");
  EXPECT_EQ(groups[2].code, "OCC");
  EXPECT_EQ(groups[1].sequences, (std::vector<std::string>{"far", "near"}));
  // "slow" on SV: the mean of 0.2 and 0.6 below threshold 1; its AUC the mean of the curve.
  EXPECT_DOUBLE_EQ(groups[1].success[0][0], 0.4);
  EXPECT_NEAR(groups[1].auc[0], 0.4 * 20.0 / 21.0, 1e-12);
  EXPECT_NEAR(groups[0].auc[1], (0.8 + 0.4 + 1.0) / 3.0 * 20.0 / 21.0, 1e-12);
  EXPECT_DOUBLE_EQ(groups[2].precision_20[1], 0.9);
  EXPECT_EQ(groups[0].precision[0].size(), 51u);
}

TEST(OtbResults, SummaryGivesMeansAndTheMedianSpeedAgainstCsrt) {
  const std::vector<OtbTrackerSummary> summary = SummariseOtb(Results());
  ASSERT_EQ(summary.size(), 2u);
  EXPECT_NEAR(summary[0].auc, (0.2 + 0.6 + 1.0) / 3.0 * 20.0 / 21.0, 1e-12);
  EXPECT_DOUBLE_EQ(summary[0].ms_per_frame, 2.0);  // median of 8, 2, 1
  // csrt's ms over slow's: 0.5, 2, 2; the median 2.
  EXPECT_DOUBLE_EQ(summary[0].speed_vs_csrt, 2.0);
  EXPECT_DOUBLE_EQ(summary[1].speed_vs_csrt, 1.0);
  EXPECT_EQ(summary[0].frames, 30);

  // Without csrt there is no ratio, and the JSON says null.
  OtbResults without = Results();
  without.trackers.pop_back();
  for (OtbSequenceResult& sequence : without.sequences) sequence.runs.pop_back();
  EXPECT_TRUE(std::isnan(SummariseOtb(without)[0].speed_vs_csrt));
  EXPECT_TRUE(OtbResultsJson(without)["summary"][0]["speed_vs_csrt_median"].is_null());
}

TEST(OtbResults, JsonHoldsTheCurvesOfEverySequenceAndGroup) {
  const nlohmann::ordered_json json = OtbResultsJson(Results());
  EXPECT_EQ(json["sequences"].size(), 3u);
  EXPECT_EQ(json["sequences"][0]["trackers"]["csrt"]["success"].size(), 21u);
  EXPECT_EQ(json["sequences"][0]["trackers"]["csrt"]["precision"].size(), 51u);
  EXPECT_EQ(json["groups"].size(), 3u);
  EXPECT_TRUE(json["groups"][0]["attribute"].is_null());
  EXPECT_EQ(json["groups"][2]["attribute"], "OCC");
  EXPECT_DOUBLE_EQ(json["groups"][2]["trackers"]["slow"]["success"][0].get<double>(), 0.2);
  EXPECT_EQ(json["precision_thresholds_px"].size(), 51u);
  EXPECT_EQ(json["command"], "attend eval-tracking --otb DIR --out REPORT");
}

TEST(OtbReport, PageHasTwoPlotsPerGroupLegendsRankedAndNoScript) {
  const std::string html = OtbReportHtml(Results());
  EXPECT_EQ(Count(html, "<svg"), 2 * 3);
  EXPECT_EQ(Count(html, "</svg>"), 2 * 3);
  EXPECT_EQ(Count(html, "<script"), 0);
  EXPECT_NE(html.find("Success plots of OPE - Occlusion (1)"), std::string::npos);
  // All sequences: csrt's AUC 0.698 before slow's 0.571, the precision legend by precision@20.
  const size_t csrt = html.find("csrt [0.698]"), slow = html.find("slow [0.571]");
  ASSERT_NE(csrt, std::string::npos);
  ASSERT_NE(slow, std::string::npos);
  EXPECT_LT(csrt, slow);
  EXPECT_NE(html.find("csrt [0.800]"), std::string::npos);
  // Per sequence, the best AUC of a row in bold: slow on near (0.571), csrt on far (0.762).
  EXPECT_NE(html.find("<td class=\"num best\">0.571</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num best\">0.762</td>"), std::string::npos);
}

TEST(SvgLinePlot, DrawsEachSeriesAsAPolylineInsideTheAxes) {
  LinePlot plot;
  plot.title = "a <title>";
  plot.x = {0.0, 0.5, 1.0};
  plot.series = {{"one [1.000]", "#123456", {1.0, 0.5, 0.0}},
                 {"two", "red", {1.0, std::nan(""), 2.0}}};
  const std::string svg = SvgLinePlot(plot);
  EXPECT_EQ(svg.rfind("<svg xmlns=\"http://www.w3.org/2000/svg\"", 0), 0u);
  EXPECT_NE(svg.find("<title>a &lt;title&gt;</title>"), std::string::npos);
  // The plot area spans x 58..446 and y 32..296 of the 460 x 340 image.
  EXPECT_NE(svg.find("points=\"58.0,32.0 252.0,164.0 446.0,296.0\""), std::string::npos) << svg;
  // The gap breaks the second series in two; its 2.0 is clamped to the top.
  EXPECT_NE(svg.find("points=\"58.0,32.0\""), std::string::npos);
  EXPECT_NE(svg.find("points=\"446.0,32.0\""), std::string::npos);
  EXPECT_NE(svg.find(">one [1.000]</text>"), std::string::npos);
  EXPECT_EQ(Count(svg, "<polyline"), 3);
}

}  // namespace
}  // namespace attend
