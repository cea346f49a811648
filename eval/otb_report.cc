#include "eval/otb_report.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "eval/html_page.h"
#include "eval/otb_sequences.h"
#include "eval/svg_plot.h"
#include "util/strings.h"

namespace attend {

namespace {

// The trackers' indices by `score`, highest first (ties in the trackers' order), as the
// toolkit orders its legends.
std::vector<size_t> Ranked(const std::vector<double>& score) {
  std::vector<size_t> order(score.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return score[a] > score[b]; });
  return order;
}

// The success plot (overlap thresholds 0..1) or the precision plot (0..50 px) of a group.
std::string GroupPlot(const OtbResults& results, const OtbGroup& group, bool success) {
  LinePlot plot;
  const std::string suffix = group.code.empty() ? std::string()
                                                : " - " + group.title + " (" +
                                                      std::to_string(group.sequences.size()) + ")";
  plot.title = std::string(success ? "Success plots of OPE" : "Precision plots of OPE") + suffix;
  if (success) {
    plot.x_label = "Overlap threshold";
    plot.y_label = "Success rate";
    plot.x = SuccessThresholds();
  } else {
    plot.x_label = "Location error threshold (px)";
    plot.y_label = "Precision";
    plot.x = PrecisionThresholds();
    plot.x_max = 50.0;
    plot.x_step = 5.0;
    plot.x_decimals = 0;
    plot.legend = LegendCorner::kBottomRight;
  }
  const std::vector<double>& score = success ? group.auc : group.precision_20;
  for (const size_t t : Ranked(score)) {
    plot.series.push_back({results.trackers[t].name + " [" + Fixed(score[t], 3) + "]",
                           ChartColour(t), success ? group.success[t] : group.precision[t]});
  }
  return SvgLinePlot(plot);
}

std::string GroupPlots(const OtbResults& results) {
  std::string html = "<section><h2>Success and precision plots</h2>";
  html +=
      "<p class=\"small\">One-pass evaluation (OPE): every tracker starts on frame 0 from the "
      "true box and runs to the end. Success: the share of frames whose box overlaps the truth "
      "by more than the threshold (IoU), the legend its mean over the thresholds 0, 0.05, ..., "
      "1 (AUC). Precision: the share of frames whose box centre lies within the threshold of "
      "the true centre, the legend its value at 20 px. Curves are the means over the group's "
      "sequences.</p>";
  for (const OtbGroup& group : OtbGroups(results)) {
    html += "<h3>" + HtmlEscape(group.title) + " (" + std::to_string(group.sequences.size()) +
            (group.sequences.size() == 1 ? " sequence" : " sequences") + ")</h3>";
    if (!group.code.empty()) {
      html += "<p class=\"small\">" + HtmlEscape(group.code) + ": " +
              HtmlEscape(Join(group.sequences, ", ")) + "</p>";
    }
    html += "<div class=\"charts\"><figure>" + GroupPlot(results, group, true) +
            "</figure><figure>" + GroupPlot(results, group, false) + "</figure></div>";
  }
  return html + "</section>\n";
}

std::string Cell(const std::string& text, bool best = false) {
  return std::string(best ? "<td class=\"num best\">" : "<td class=\"num\">") + text + "</td>";
}

std::string SummaryTable(const OtbResults& results) {
  std::string html =
      "<section><h2>Summary</h2><table><tr><th>tracker</th><th>kind</th><th>success AUC</th>"
      "<th>precision@20</th><th>ms per frame (median)</th><th>times faster than csrt "
      "(median)</th><th>frames not found</th><th>frames lost</th><th>not started</th></tr>";
  const std::vector<OtbTrackerSummary> summaries = SummariseOtb(results);
  double best_auc = 0.0, best_precision = 0.0;
  for (const OtbTrackerSummary& s : summaries) {
    best_auc = std::max(best_auc, s.auc);
    best_precision = std::max(best_precision, s.precision_20);
  }
  for (const OtbTrackerSummary& s : summaries) {
    html += "<tr><td>" + HtmlEscape(s.name) + "</td><td>" + HtmlEscape(s.description) + "</td>" +
            Cell(HtmlNumber(s.auc), s.auc == best_auc) +
            Cell(HtmlNumber(s.precision_20), s.precision_20 == best_precision) +
            Cell(HtmlNumber(s.ms_per_frame, 2)) + Cell(HtmlNumber(s.speed_vs_csrt, 2)) +
            Cell(std::to_string(s.not_found)) + Cell(std::to_string(s.lost_frames)) +
            Cell(std::to_string(s.not_started)) + "</tr>";
  }
  return html +
         "</table><p class=\"small\">AUC and precision@20: means over the sequences (the "
         "legends of the plots of all sequences). Time: one <code>Track()</code> call on a "
         "frame already decoded, the trackers taking turns frame by frame on one OpenCV "
         "thread; the median over the sequences. Times faster than csrt: per sequence csrt's "
         "ms per frame over the tracker's, the median over the sequences. Frames not found: "
         "the tracker said it did not find the target (it answers with its last box). Frames "
         "lost: from the frame a target was lost in to the end (the last box kept).</p>"
         "</section>\n";
}

// The best value of `value(run)` among the trackers of a sequence.
template <typename Value>
double Best(const OtbSequenceResult& sequence, Value value) {
  double best = -1.0;
  for (const OtbRun& run : sequence.runs) best = std::max(best, value(run));
  return best;
}

// One column per tracker with `value(run)`, the best of the row in bold.
template <typename Value>
std::string ScoreCells(const OtbSequenceResult& sequence, Value value) {
  const double best = Best(sequence, value);
  std::string html;
  for (const OtbRun& run : sequence.runs) html += Cell(HtmlNumber(value(run)), value(run) == best);
  return html;
}

std::string SequenceTable(const OtbResults& results) {
  const std::string trackers = std::to_string(results.trackers.size());
  std::string html =
      "<section><h2>Per sequence</h2><table><tr><th rowspan=\"2\">sequence</th>"
      "<th rowspan=\"2\">frames</th><th rowspan=\"2\">size</th><th rowspan=\"2\">attributes"
      "</th><th colspan=\"" +
      trackers + "\">success AUC</th><th colspan=\"" + trackers +
      "\">precision@20</th><th colspan=\"" + trackers + "\">ms per frame</th></tr><tr>";
  std::string names;
  for (const OtbTracker& tracker : results.trackers)
    names += "<th>" + HtmlEscape(tracker.name) + "</th>";
  html += names + names + names + "</tr>";
  for (const OtbSequenceResult& sequence : results.sequences) {
    html += "<tr><td>" + HtmlEscape(sequence.name) + "</td>" +
            Cell(std::to_string(sequence.frames)) + "<td>" + std::to_string(sequence.width) + "x" +
            std::to_string(sequence.height) + "</td><td>" +
            HtmlEscape(Join(sequence.attributes, ", ")) + "</td>";
    html += ScoreCells(sequence, [](const OtbRun& run) { return run.scores.success_auc; });
    html += ScoreCells(sequence, [](const OtbRun& run) { return run.scores.precision_20; });
    for (const OtbRun& run : sequence.runs) {
      html += run.updates > 0 ? Cell(HtmlNumber(run.ms_per_frame, 2))
                              : std::string("<td class=\"missing\">&ndash;</td>");
    }
    html += "</tr>";
  }
  return html +
         "</table><p class=\"small\">Best of each row in bold. Each tracker's boxes are in "
         "<code>tracks/&lt;tracker&gt;/&lt;sequence&gt;.csv</code> (the tracks.csv format; "
         "<code>attend eval-tracking</code> of one against the sequence's ground truth gives "
         "the same AUC).</p></section>\n";
}

std::string TrackerList(const OtbResults& results) {
  std::string html = "<section><h2>Trackers</h2><ul>";
  for (const OtbTracker& tracker : results.trackers) {
    html +=
        "<li><b>" + HtmlEscape(tracker.name) + "</b>: " + HtmlEscape(tracker.description) + "</li>";
  }
  return html + "</ul><p class=\"small\">The options of each are in results.json.</p></section>\n";
}

}  // namespace

std::string OtbReportHtml(const OtbResults& results) {
  int frames = 0;
  for (const OtbSequenceResult& sequence : results.sequences) frames += sequence.frames;
  std::string html =
      HtmlPageStart("attend eval-tracking --otb",
                    "OTB one-pass evaluation: " + std::to_string(results.sequences.size()) +
                        " sequences, " + std::to_string(frames) + " frames",
                    results.command_line);
  html += "<p class=\"small\">" + HtmlEscape(results.dir) + "; " + HtmlEscape(results.date) +
          "; CPU " + HtmlEscape(results.cpu) + "; OpenCV " + HtmlEscape(results.opencv) + ", " +
          std::to_string(results.opencv_threads) + " thread; " + Fixed(results.seconds, 1) +
          " s</p>\n";
  html += HtmlNotes(results.notes);
  html += SummaryTable(results);
  html += GroupPlots(results);
  html += SequenceTable(results);
  html += TrackerList(results);
  return html + HtmlPageEnd();
}

}  // namespace attend
