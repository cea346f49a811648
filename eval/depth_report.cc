#include "eval/depth_report.h"

#include <algorithm>
#include <cmath>

#include "eval/html_page.h"
#include "eval/run_depth.h"
#include "eval/svg_plot.h"
#include "pipeline/overlay.h"

namespace attend {

namespace {

// The overlay's colour of target `id` (BGR there) as CSS.
std::string CssColour(int id) {
  const cv::Scalar bgr = TargetColour(id);
  return "rgb(" + std::to_string(static_cast<int>(bgr[2])) + "," +
         std::to_string(static_cast<int>(bgr[1])) + "," +
         std::to_string(static_cast<int>(bgr[0])) + ")";
}

// The value below which a share `q` of `values` lie (nearest rank); `values` is sorted here.
double Quantile(std::vector<double>* values, double q) {
  std::sort(values->begin(), values->end());
  const auto index = static_cast<size_t>(std::lround(q * static_cast<double>(values->size() - 1)));
  return (*values)[index];
}

// The smallest step between consecutive frames of the run (1 unless it was strided).
int FrameStep(const std::vector<FrameRecord>& frames) {
  int step = 0;
  for (size_t i = 1; i < frames.size(); ++i) {
    const int gap = frames[i].frame - frames[i - 1].frame;
    if (gap > 0 && (step == 0 || gap < step)) step = gap;
  }
  return std::max(1, step);
}

// The region the top view shows: the camera and the 2nd to 98th percentiles of the positions,
// with a margin; at least a metre each way.
void PlotRegion(const std::vector<TopViewTrack>& tracks, PathPlot* plot) {
  std::vector<double> xs, zs;
  for (const TopViewTrack& track : tracks) {
    xs.insert(xs.end(), track.x_m.begin(), track.x_m.end());
    zs.insert(zs.end(), track.z_m.begin(), track.z_m.end());
  }
  const double q = xs.size() >= 50 ? 0.02 : 0.0;
  double x_lo = std::min(0.0, Quantile(&xs, q)), x_hi = std::max(0.0, Quantile(&xs, 1.0 - q));
  double z_hi = std::max(0.0, Quantile(&zs, 1.0 - q));
  const double margin = 0.08 * std::max({x_hi - x_lo, z_hi, 1.0});
  plot->x_min = x_lo - margin;
  plot->x_max = x_hi + margin;
  plot->y_min = 0.0;
  plot->y_max = z_hi + margin;
}

int OutsideRegion(const std::vector<TopViewTrack>& tracks, const PathPlot& plot) {
  // The plot widens the region to equal scale, so this counts at most what is clipped.
  int outside = 0;
  for (const TopViewTrack& track : tracks) {
    for (size_t i = 0; i < track.x_m.size(); ++i) {
      outside += track.x_m[i] < plot.x_min || track.x_m[i] > plot.x_max ||
                 track.z_m[i] < plot.y_min || track.z_m[i] > plot.y_max;
    }
  }
  return outside;
}

std::string Cell(const std::string& text) { return "<td>" + text + "</td>"; }

std::string RunsTable(const std::vector<RunData>& runs, const std::vector<std::string>& labels) {
  std::string html =
      "<table><tr><th>run</th><th>targets seen (target-frames)</th>"
      "<th>with a disparity</th><th>with a position</th><th>mean disparity sd (px)</th>"
      "<th>mean depth Z (m)</th><th>mean depth sd (m)</th></tr>";
  for (size_t i = 0; i < runs.size(); ++i) {
    const RunDepth d = SummariseDepth(runs[i].frames);
    html += "<tr>" + Cell(HtmlEscape(labels[i])) + Cell(std::to_string(d.target_frames)) +
            Cell(std::to_string(d.with_disparity)) + Cell(std::to_string(d.with_position)) +
            Cell(HtmlNumber(d.mean_disparity_sd_px, 2)) + Cell(HtmlNumber(d.mean_depth_m, 2)) +
            Cell(HtmlNumber(d.mean_depth_sd_m, 3)) + "</tr>";
  }
  return html + "</table>";
}

std::string DifferencesTable(const DepthComparison& depth, const std::string& label) {
  std::string html = "<h3>" + HtmlEscape(label) +
                     " against A: matched targets</h3><table><tr><th>A id</th>"
                     "<th>id</th><th>frames with both disparities</th><th>mean disparity "
                     "difference (px)</th><th>frames with both positions</th><th>mean distance "
                     "(m)</th><th>mean Z difference (m)</th></tr>";
  for (const TargetDepthDifference& t : depth.targets) {
    html += "<tr>" + Cell(std::to_string(t.id_a)) + Cell(std::to_string(t.id_b)) +
            Cell(std::to_string(t.disparity_frames)) +
            Cell(HtmlNumber(t.mean_disparity_difference_px, 2)) +
            Cell(std::to_string(t.position_frames)) + Cell(HtmlNumber(t.mean_distance_m, 3)) +
            Cell(HtmlNumber(t.mean_depth_difference_m, 3)) + "</tr>";
  }
  return html + "</table><p class=\"small\">Over every matched pair and frame: mean |disparity " +
         "difference| " + HtmlNumber(depth.mean_abs_disparity_difference_px, 2) +
         " px, mean distance " + HtmlNumber(depth.mean_distance_m, 3) +
         " m (this run minus A).</p>";
}

}  // namespace

std::string TopViewSvg(const std::vector<FrameRecord>& frames, const std::string& title,
                       const std::string& id, int dot_every, int* clipped) {
  const std::vector<TopViewTrack> tracks = TopViewTracks(frames);
  if (clipped != nullptr) *clipped = 0;
  if (tracks.empty()) return "";
  const int first = frames.front().frame, last = frames.back().frame;
  const int step = FrameStep(frames);
  if (dot_every <= 0) dot_every = step * std::max(1, (last - first) / (12 * step));
  PathPlot plot;
  plot.id = id;
  plot.title = title;
  plot.x_label = "X (m), right";
  plot.y_label = "Z (m), forward";
  plot.origin_label = "camera";
  PlotRegion(tracks, &plot);
  if (clipped != nullptr) *clipped = OutsideRegion(tracks, plot);
  for (const TopViewTrack& track : tracks) {
    PathSeries series;
    series.label = "#" + std::to_string(track.id);
    series.colour = CssColour(track.id);
    for (size_t i = 0; i < track.frames.size(); ++i) {
      const int frame = track.frames[i];
      if (i > 0 && frame - track.frames[i - 1] > 3 * step) {
        series.x.push_back(std::nan(""));  // unseen for a while: break the line
        series.y.push_back(std::nan(""));
        series.dot_opacity.push_back(0.0);
      }
      series.x.push_back(track.x_m[i]);
      series.y.push_back(track.z_m[i]);
      const double t = last > first ? static_cast<double>(frame - first) / (last - first) : 1.0;
      series.dot_opacity.push_back((frame - first) % dot_every == 0 ? 0.15 + 0.85 * t : 0.0);
    }
    plot.series.push_back(std::move(series));
  }
  return SvgPathPlot(plot);
}

std::string DepthSectionHtml(const std::vector<RunData>& runs,
                             const std::vector<RunComparison>& comparisons,
                             const std::vector<std::string>& labels) {
  bool any = false;
  for (const RunData& run : runs) any = any || SummariseDepth(run.frames).any();
  if (!any) return "";
  std::string html = "<section><h2>Depth</h2>" + RunsTable(runs, labels);
  for (size_t i = 0; i < comparisons.size(); ++i) {
    if (comparisons[i].depth) html += DifferencesTable(*comparisons[i].depth, labels[i + 1]);
  }
  std::string views;
  for (size_t i = 0; i < runs.size(); ++i) {
    int clipped = 0;
    const std::string svg = TopViewSvg(runs[i].frames, "Top view: " + labels[i],
                                       "topview-" + std::to_string(i), 0, &clipped);
    if (svg.empty()) continue;
    views += "<figure>" + svg + "<figcaption>" + HtmlEscape(labels[i]);
    if (clipped > 0) {
      views += ": " + std::to_string(clipped) + " positions beyond the plotted area (clipped)";
    }
    views += "</figcaption></figure>";
  }
  if (!views.empty()) {
    html += "<h3>Top views</h3><div class=\"charts\">" + views +
            "</div><p class=\"small\">The attended objects seen from above, in metres in the "
            "left camera's frame (the camera at the origin, looking up the page): one line a "
            "target, in its overlay colour, labelled with its id where it was last seen; a dot "
            "every few frames, fainter early in the run and solid at its end.</p>";
  }
  return html + "</section>\n";
}

}  // namespace attend
