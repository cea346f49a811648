#include "eval/svg_plot.h"

#include <algorithm>
#include <cmath>

#include "eval/html_page.h"
#include "util/strings.h"

namespace attend {

namespace {

// The plot area inside the image, in pixels.
struct Frame {
  double left = 58.0, top = 32.0, right = 0.0, bottom = 0.0;
};

std::string Px(double value) { return Fixed(value, 1); }

double ToX(const LinePlot& plot, const Frame& f, double x) {
  return f.left + (x - plot.x_min) / (plot.x_max - plot.x_min) * (f.right - f.left);
}

double ToY(const LinePlot& plot, const Frame& f, double y) {
  return f.bottom - (y - plot.y_min) / (plot.y_max - plot.y_min) * (f.bottom - f.top);
}

std::string Text(double x, double y, const std::string& text, const std::string& attributes) {
  return "<text x=\"" + Px(x) + "\" y=\"" + Px(y) + "\" " + attributes + ">" + HtmlEscape(text) +
         "</text>";
}

// Grid lines, ticks and their labels, the frame and the axis labels.
std::string Axes(const LinePlot& plot, const Frame& f) {
  std::string svg = "<g stroke=\"#e3e3e3\" stroke-width=\"1\">";
  std::string labels = "<g font-size=\"11\" fill=\"#333\">";
  const int x_ticks = static_cast<int>(std::lround((plot.x_max - plot.x_min) / plot.x_step));
  for (int i = 0; i <= x_ticks; ++i) {
    const double value = plot.x_min + i * plot.x_step;
    const double x = ToX(plot, f, value);
    svg += "<line x1=\"" + Px(x) + "\" y1=\"" + Px(f.top) + "\" x2=\"" + Px(x) + "\" y2=\"" +
           Px(f.bottom) + "\"/>";
    labels += Text(x, f.bottom + 15, Fixed(value, plot.x_decimals), "text-anchor=\"middle\"");
  }
  const int y_ticks = static_cast<int>(std::lround((plot.y_max - plot.y_min) / plot.y_step));
  for (int i = 0; i <= y_ticks; ++i) {
    const double value = plot.y_min + i * plot.y_step;
    const double y = ToY(plot, f, value);
    svg += "<line x1=\"" + Px(f.left) + "\" y1=\"" + Px(y) + "\" x2=\"" + Px(f.right) + "\" y2=\"" +
           Px(y) + "\"/>";
    labels += Text(f.left - 6, y + 4, Fixed(value, plot.y_decimals), "text-anchor=\"end\"");
  }
  svg += "</g>" + labels + "</g>";
  svg += "<rect x=\"" + Px(f.left) + "\" y=\"" + Px(f.top) + "\" width=\"" + Px(f.right - f.left) +
         "\" height=\"" + Px(f.bottom - f.top) + "\" fill=\"none\" stroke=\"#555\"/>";
  svg += Text((f.left + f.right) / 2, f.bottom + 34, plot.x_label,
              "text-anchor=\"middle\" font-size=\"12\"");
  const double middle = (f.top + f.bottom) / 2;
  svg += Text(
      16, middle, plot.y_label,
      "text-anchor=\"middle\" font-size=\"12\" transform=\"rotate(-90 16 " + Px(middle) + ")\"");
  svg += Text(plot.width / 2.0, 18, plot.title,
              "text-anchor=\"middle\" font-size=\"13\" font-weight=\"bold\"");
  return svg;
}

// One polyline per run of finite values of the series.
std::string Curve(const LinePlot& plot, const Frame& f, const PlotSeries& series) {
  std::string svg;
  std::string points;
  const auto flush = [&] {
    if (!points.empty()) {
      svg += "<polyline fill=\"none\" stroke=\"" + HtmlEscape(series.colour) +
             "\" stroke-width=\"2\" points=\"" + points + "\"/>";
    }
    points.clear();
  };
  const size_t count = std::min(plot.x.size(), series.y.size());
  for (size_t i = 0; i < count; ++i) {
    if (!std::isfinite(series.y[i])) {
      flush();
      continue;
    }
    const double y = std::clamp(series.y[i], plot.y_min, plot.y_max);
    if (!points.empty()) points += ' ';
    points += Px(ToX(plot, f, plot.x[i])) + "," + Px(ToY(plot, f, y));
  }
  flush();
  return svg;
}

// The legend box in its corner of the plot area, a line of the series' colour before each label.
std::string Legend(const LinePlot& plot, const Frame& f) {
  if (plot.series.empty()) return "";
  constexpr double kLine = 17.0, kPad = 6.0, kSample = 22.0, kCharWidth = 6.6;
  size_t longest = 0;
  for (const PlotSeries& s : plot.series) longest = std::max(longest, s.label.size());
  const double width = kPad * 3 + kSample + kCharWidth * static_cast<double>(longest);
  const double height = kPad * 2 + kLine * static_cast<double>(plot.series.size());
  const double x = plot.legend == LegendCorner::kBottomLeft ? f.left + 8 : f.right - 8 - width;
  const double y = f.bottom - 8 - height;
  std::string svg = "<g font-size=\"12\"><rect x=\"" + Px(x) + "\" y=\"" + Px(y) + "\" width=\"" +
                    Px(width) + "\" height=\"" + Px(height) +
                    "\" fill=\"#fff\" fill-opacity=\"0.9\" stroke=\"#999\"/>";
  for (size_t i = 0; i < plot.series.size(); ++i) {
    const double line_y = y + kPad + kLine * (static_cast<double>(i) + 0.5);
    svg += "<line x1=\"" + Px(x + kPad) + "\" y1=\"" + Px(line_y) + "\" x2=\"" +
           Px(x + kPad + kSample) + "\" y2=\"" + Px(line_y) + "\" stroke=\"" +
           HtmlEscape(plot.series[i].colour) + "\" stroke-width=\"2\"/>";
    svg += Text(x + 2 * kPad + kSample, line_y + 4, plot.series[i].label, "fill=\"#222\"");
  }
  return svg + "</g>";
}

}  // namespace

std::string SvgLinePlot(const LinePlot& plot) {
  Frame f;
  f.right = plot.width - 14.0;
  f.bottom = plot.height - 44.0;
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
                    std::to_string(plot.width) + "\" height=\"" + std::to_string(plot.height) +
                    "\" viewBox=\"0 0 " + std::to_string(plot.width) + " " +
                    std::to_string(plot.height) + "\" role=\"img\" font-family=\"sans-serif\">";
  svg += "<title>" + HtmlEscape(plot.title) + "</title>";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>";
  svg += Axes(plot, f);
  for (const PlotSeries& series : plot.series) svg += Curve(plot, f, series);
  svg += Legend(plot, f);
  return svg + "</svg>";
}

}  // namespace attend
