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

// One axis: its range, where its ticks are and how they read, and its label.
struct Axis {
  double min = 0.0, max = 1.0;
  std::vector<double> ticks;
  int decimals = 1;
  std::string label;
};

double ToX(const Axis& axis, const Frame& f, double x) {
  return f.left + (x - axis.min) / (axis.max - axis.min) * (f.right - f.left);
}

double ToY(const Axis& axis, const Frame& f, double y) {
  return f.bottom - (y - axis.min) / (axis.max - axis.min) * (f.bottom - f.top);
}

std::string Text(double x, double y, const std::string& text, const std::string& attributes) {
  return "<text x=\"" + Px(x) + "\" y=\"" + Px(y) + "\" " + attributes + ">" + HtmlEscape(text) +
         "</text>";
}

// min, min + step, ... up to max (the line plot's ticks).
std::vector<double> StepTicks(double min, double max, double step) {
  std::vector<double> ticks;
  const int count = static_cast<int>(std::lround((max - min) / step));
  for (int i = 0; i <= count; ++i) ticks.push_back(min + i * step);
  return ticks;
}

// Grid lines, ticks and their labels, the frame, the axis labels and the title.
std::string Axes(const Axis& x_axis, const Axis& y_axis, const std::string& title, int width,
                 const Frame& f) {
  std::string svg = "<g stroke=\"#e3e3e3\" stroke-width=\"1\">";
  std::string labels = "<g font-size=\"11\" fill=\"#333\">";
  for (const double value : x_axis.ticks) {
    const double x = ToX(x_axis, f, value);
    svg += "<line x1=\"" + Px(x) + "\" y1=\"" + Px(f.top) + "\" x2=\"" + Px(x) + "\" y2=\"" +
           Px(f.bottom) + "\"/>";
    labels += Text(x, f.bottom + 15, Fixed(value, x_axis.decimals), "text-anchor=\"middle\"");
  }
  for (const double value : y_axis.ticks) {
    const double y = ToY(y_axis, f, value);
    svg += "<line x1=\"" + Px(f.left) + "\" y1=\"" + Px(y) + "\" x2=\"" + Px(f.right) + "\" y2=\"" +
           Px(y) + "\"/>";
    labels += Text(f.left - 6, y + 4, Fixed(value, y_axis.decimals), "text-anchor=\"end\"");
  }
  svg += "</g>" + labels + "</g>";
  svg += "<rect x=\"" + Px(f.left) + "\" y=\"" + Px(f.top) + "\" width=\"" + Px(f.right - f.left) +
         "\" height=\"" + Px(f.bottom - f.top) + "\" fill=\"none\" stroke=\"#555\"/>";
  svg += Text((f.left + f.right) / 2, f.bottom + 34, x_axis.label,
              "text-anchor=\"middle\" font-size=\"12\"");
  const double middle = (f.top + f.bottom) / 2;
  svg += Text(
      16, middle, y_axis.label,
      "text-anchor=\"middle\" font-size=\"12\" transform=\"rotate(-90 16 " + Px(middle) + ")\"");
  svg += Text(width / 2.0, 18, title, "text-anchor=\"middle\" font-size=\"13\" font-weight=\"bold\"");
  return svg;
}

Axis XAxis(const LinePlot& plot) {
  return {plot.x_min, plot.x_max, StepTicks(plot.x_min, plot.x_max, plot.x_step),
          plot.x_decimals, plot.x_label};
}

Axis YAxis(const LinePlot& plot) {
  return {plot.y_min, plot.y_max, StepTicks(plot.y_min, plot.y_max, plot.y_step),
          plot.y_decimals, plot.y_label};
}

// One polyline per run of finite values of the series.
std::string Curve(const LinePlot& plot, const Frame& f, const PlotSeries& series) {
  const Axis x_axis = XAxis(plot), y_axis = YAxis(plot);
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
    points += Px(ToX(x_axis, f, plot.x[i])) + "," + Px(ToY(y_axis, f, y));
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
  svg += Axes(XAxis(plot), YAxis(plot), plot.title, plot.width, f);
  for (const PlotSeries& series : plot.series) svg += Curve(plot, f, series);
  svg += Legend(plot, f);
  return svg + "</svg>";
}

double NiceStep(double span, int intervals) {
  const double raw = span / std::max(1, intervals);
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (const double factor : {1.0, 2.0, 5.0, 10.0}) {
    if (factor * power >= raw * (1.0 - 1e-9)) return factor * power;
  }
  return 10.0 * power;
}

namespace {

// Multiples of `step` from min to max.
std::vector<double> MultipleTicks(double min, double max, double step) {
  std::vector<double> ticks;
  const double first = std::ceil(min / step - 1e-9);
  for (double k = first; k * step <= max + step * 1e-9; k += 1.0) {
    ticks.push_back(k * step == 0.0 ? 0.0 : k * step);  // no "-0.0"
  }
  return ticks;
}

int StepDecimals(double step) {
  return step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
}

// The plot's axes at equal scale: the region widened, x about its centre, y upwards.
void EqualScaleAxes(const PathPlot& plot, const Frame& f, Axis* x_axis, Axis* y_axis) {
  const double x_span = std::max(plot.x_max - plot.x_min, 1e-9);
  const double y_span = std::max(plot.y_max - plot.y_min, 1e-9);
  const double per_px = std::max(x_span / (f.right - f.left), y_span / (f.bottom - f.top));
  const double centre = (plot.x_min + plot.x_max) / 2;
  x_axis->min = centre - per_px * (f.right - f.left) / 2;
  x_axis->max = centre + per_px * (f.right - f.left) / 2;
  y_axis->min = plot.y_min;
  y_axis->max = plot.y_min + per_px * (f.bottom - f.top);
  const double step =
      NiceStep(std::max(x_axis->max - x_axis->min, y_axis->max - y_axis->min), 8);
  x_axis->ticks = MultipleTicks(x_axis->min, x_axis->max, step);
  y_axis->ticks = MultipleTicks(y_axis->min, y_axis->max, step);
  x_axis->decimals = y_axis->decimals = StepDecimals(step);
  x_axis->label = plot.x_label;
  y_axis->label = plot.y_label;
}

// A path: its polylines (broken at non-finite points), its dots, and its label at its end.
std::string Path(const Axis& x_axis, const Axis& y_axis, const Frame& f, const PathSeries& series) {
  const std::string colour = HtmlEscape(series.colour);
  std::string lines, dots, points;
  const auto flush = [&] {
    if (!points.empty()) {
      lines += "<polyline fill=\"none\" stroke=\"" + colour + "\" stroke-width=\"2\" points=\"" +
               points + "\"/>";
    }
    points.clear();
  };
  const size_t count = std::min(series.x.size(), series.y.size());
  double last_x = std::nan(""), last_y = std::nan("");
  for (size_t i = 0; i < count; ++i) {
    if (!std::isfinite(series.x[i]) || !std::isfinite(series.y[i])) {
      flush();
      continue;
    }
    last_x = ToX(x_axis, f, series.x[i]);
    last_y = ToY(y_axis, f, series.y[i]);
    if (!points.empty()) points += ' ';
    points += Px(last_x) + "," + Px(last_y);
    const double opacity = i < series.dot_opacity.size() ? series.dot_opacity[i] : 0.0;
    if (std::isfinite(opacity) && opacity > 0.0) {
      dots += "<circle cx=\"" + Px(last_x) + "\" cy=\"" + Px(last_y) + "\" r=\"3.5\" fill=\"" +
              colour + "\" fill-opacity=\"" + Fixed(std::min(opacity, 1.0), 2) +
              "\" stroke=\"#222\" stroke-opacity=\"" + Fixed(std::min(opacity, 1.0), 2) +
              "\" stroke-width=\"0.7\"/>";
    }
  }
  flush();
  std::string svg = "<g>" + lines + dots;
  if (std::isfinite(last_x) && !series.label.empty()) {
    // Dark on a white halo: legible over any line; the line and dots carry the colour.
    svg += Text(last_x + 6, last_y - 6, series.label,
                "font-size=\"12\" font-weight=\"bold\" fill=\"#222\" stroke=\"#fff\" "
                "stroke-width=\"3\" paint-order=\"stroke\"");
  }
  return svg + "</g>";
}

// The marker at the origin: a triangle pointing up (forward), with its label below.
std::string OriginMarker(const Axis& x_axis, const Axis& y_axis, const Frame& f,
                         const std::string& label) {
  const double x = ToX(x_axis, f, 0.0), y = ToY(y_axis, f, 0.0);
  return "<g><polygon points=\"" + Px(x - 7) + "," + Px(y) + " " + Px(x + 7) + "," + Px(y) + " " +
         Px(x) + "," + Px(y - 12) + "\" fill=\"#222\"/>" +
         Text(x, y - 16, label, "text-anchor=\"middle\" font-size=\"11\" fill=\"#222\"") + "</g>";
}

}  // namespace

std::string SvgPathPlot(const PathPlot& plot) {
  Frame f;
  f.right = plot.width - 14.0;
  f.bottom = plot.height - 44.0;
  Axis x_axis, y_axis;
  EqualScaleAxes(plot, f, &x_axis, &y_axis);
  const std::string clip = "clip-" + HtmlEscape(plot.id);
  std::string svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" +
                    std::to_string(plot.width) + "\" height=\"" + std::to_string(plot.height) +
                    "\" viewBox=\"0 0 " + std::to_string(plot.width) + " " +
                    std::to_string(plot.height) + "\" role=\"img\" font-family=\"sans-serif\">";
  svg += "<title>" + HtmlEscape(plot.title) + "</title>";
  svg += "<defs><clipPath id=\"" + clip + "\"><rect x=\"" + Px(f.left) + "\" y=\"" + Px(f.top) +
         "\" width=\"" + Px(f.right - f.left) + "\" height=\"" + Px(f.bottom - f.top) +
         "\"/></clipPath></defs>";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"#fff\"/>";
  svg += Axes(x_axis, y_axis, plot.title, plot.width, f);
  svg += "<g clip-path=\"url(#" + clip + ")\">";
  if (!plot.origin_label.empty()) svg += OriginMarker(x_axis, y_axis, f, plot.origin_label);
  for (const PathSeries& series : plot.series) svg += Path(x_axis, y_axis, f, series);
  return svg + "</g></svg>";
}

}  // namespace attend
