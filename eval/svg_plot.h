// Plots as inline SVG, for HTML pages that must open without scripts or external files: a line
// plot (axes with ticks and a grid, one polyline a series, a legend in a corner of the plot
// area; eval/otb_report.h's OTB success and precision plots), and a plan view of paths at equal
// scale on both axes (the top view of the targets' tracks in metres, eval/depth_report.h).
#pragma once

#include <string>
#include <vector>

namespace attend {

struct PlotSeries {
  std::string label;      // the legend's text
  std::string colour;     // a CSS colour
  std::vector<double> y;  // one value per abscissa of the plot; non-finite values break the line
};

enum class LegendCorner { kBottomLeft, kBottomRight };

struct LinePlot {
  std::string title;
  std::string x_label;
  std::string y_label;
  std::vector<double> x;                          // the abscissae, shared by every series
  double x_min = 0.0, x_max = 1.0, x_step = 0.1;  // the x axis and its ticks
  double y_min = 0.0, y_max = 1.0, y_step = 0.1;  // the y axis and its ticks
  int x_decimals = 1, y_decimals = 1;             // decimals of the tick labels
  LegendCorner legend = LegendCorner::kBottomLeft;
  std::vector<PlotSeries> series;  // drawn, and listed in the legend, in this order
  int width = 460, height = 340;   // pixels
};

// The plot as one <svg> element (with a <title> for screen readers), text escaped for HTML.
std::string SvgLinePlot(const LinePlot& plot);

// A path of points in the plane: its polyline and dots in its colour, and a label (dark on a
// white halo) at its last point.
struct PathSeries {
  std::string label;      // drawn beside its last point
  std::string colour;     // a CSS colour
  std::vector<double> x;  // the points; a non-finite coordinate breaks the line
  std::vector<double> y;
  // Per point: a dot of this opacity (0..1; 0 or non-finite: none). Empty: no dots.
  std::vector<double> dot_opacity;
};

struct PathPlot {
  std::string id;  // unique in the page (names its clip path); letters, digits, '-' and '_'
  std::string title;
  std::string x_label;
  std::string y_label;
  // The region to show, widened (x about its centre, y upwards) so that a unit has the same
  // length on both axes; what lies outside is clipped. Ticks are at multiples of NiceStep.
  double x_min = -1.0, x_max = 1.0, y_min = 0.0, y_max = 1.0;
  std::string origin_label;  // not empty: a marker at (0, 0), pointing up, with this label
  std::vector<PathSeries> series;  // drawn in this order
  int width = 560, height = 460;   // pixels
};

// The plot as one <svg> element (with a <title>), text escaped for HTML.
std::string SvgPathPlot(const PathPlot& plot);

// A tick step, 1, 2 or 5 times a power of ten, giving at most about `intervals` intervals over
// `span` (> 0).
double NiceStep(double span, int intervals);

}  // namespace attend
