// A line plot as inline SVG: axes with ticks and a grid, one polyline a series, a legend in a
// corner of the plot area. For HTML pages that must open without scripts or external files
// (eval/otb_report.h, the OTB success and precision plots).
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

}  // namespace attend
