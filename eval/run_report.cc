#include "eval/run_report.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <sstream>

#include "eval/depth_report.h"
#include "io/image_file.h"
#include "io/pfm.h"
#include "util/json_text.h"
#include "util/strings.h"

namespace attend {

namespace {

namespace fs = std::filesystem;

std::string RunLabel(const RunData& run, std::size_t index) {
  const std::string name = fs::path(run.dir).filename().string();
  return std::string(1, static_cast<char>('A' + index % 26)) + " (" +
         (name.empty() ? run.dir : name) + ")";
}

// A thumbnail of an image as a data: URL, "" when the image is missing.
std::string Thumbnail(cv::Mat image, int width) {
  if (image.empty()) return "";
  const double scale = static_cast<double>(width) / image.cols;
  if (scale < 1.0) cv::resize(image, image, cv::Size(), scale, scale, cv::INTER_AREA);
  std::vector<unsigned char> png;
  if (!EncodeImage(".png", image, &png)) return "";
  return "data:image/png;base64," + Base64(png);
}

cv::Mat OverlayImage(const std::string& run, int frame) {
  const std::string path = DumpPath(run, "overlay", frame, "png");
  return fs::exists(path) ? ReadImageFileOrEmpty(path, cv::IMREAD_COLOR) : cv::Mat();
}

// The saliency map in false colour, from the PFM dump or else the PNG preview.
cv::Mat SaliencyImage(const std::string& run, int frame) {
  cv::Mat grey;
  const std::string pfm = DumpPath(run, "saliency", frame, "pfm");
  const std::string png = DumpPath(run, "saliency", frame, "png");
  if (fs::exists(pfm)) {
    const cv::Mat map = ReadPfm(pfm);
    if (map.channels() != 1) return {};
    map.convertTo(grey, CV_8U, 255.0);
  } else if (fs::exists(png)) {
    grey = ReadImageFileOrEmpty(png, cv::IMREAD_GRAYSCALE);
  }
  if (grey.empty()) return {};
  cv::Mat colour;
  cv::applyColorMap(grey, colour, cv::COLORMAP_INFERNO);
  return colour;
}

std::string ImageCell(const std::string& url, const std::string& caption) {
  if (url.empty()) return "<td class=\"missing\">" + HtmlEscape(caption) + ": not dumped</td>";
  return "<td><img src=\"" + url + "\" alt=\"" + HtmlEscape(caption) + "\"><br>" + HtmlEscape(caption) +
         "</td>";
}

std::string Notes(const ReportInput& input) {
  std::vector<std::string> notes;
  for (const RunComparison& c : input.comparisons) {
    for (const std::string& note : c.notes)
      notes.push_back(c.run_b + " vs " + c.run_a + ": " + note);
  }
  if (input.comparisons.empty() && !input.runs.empty() && input.runs[0].interrupted) {
    notes.push_back(input.runs[0].dir + " was interrupted");
  }
  if (!input.chart.found()) notes.push_back(ChartLibraryMissingNote(input.chart));
  return HtmlNotes(notes);
}

std::string RunsTable(const ReportInput& input) {
  std::string html =
      "<section><h2>Runs</h2><table><tr><th>run</th><th>folder</th>"
      "<th>sequence</th><th>frames</th><th>targets</th><th>mean ms a frame</th>"
      "</tr>";
  for (std::size_t i = 0; i < input.runs.size(); ++i) {
    const RunData& run = input.runs[i];
    double total = 0.0;
    for (const auto& stage : run.mean_timings_ms) total += stage.second;
    html += "<tr><td>" + HtmlEscape(RunLabel(run, i)) + "</td><td>" + HtmlEscape(run.dir) + "</td><td>" +
            HtmlEscape(run.sequence) + "</td><td>" + std::to_string(run.frames.size()) + "</td><td>" +
            std::to_string(SummariseTargets(run.frames).size()) + "</td><td>" + HtmlNumber(total, 2) +
            "</td></tr>";
  }
  return html + "</table></section>\n";
}

std::string AttentionTable(const ReportInput& input) {
  std::string html = "<section><h2>Attention against ground truth</h2>";
  bool any = false;
  for (const RunData& run : input.runs) any = any || run.attention.has_value();
  if (!any) {
    return html +
           "<p>No run's sequence folder has gt/objects.csv: nothing to score "
           "(<code>attend eval</code>).</p></section>\n";
  }
  html +=
      "<table><tr><th>run</th><th>objects</th><th>attended</th><th>coverage</th>"
      "<th>mean latency (frames)</th><th>revisits</th><th>identity switches</th>"
      "<th>mean IoU</th></tr>";
  for (std::size_t i = 0; i < input.runs.size(); ++i) {
    const RunData& run = input.runs[i];
    html += "<tr><td>" + HtmlEscape(RunLabel(run, i)) + "</td>";
    if (!run.attention) {
      html += "<td colspan=\"7\" class=\"missing\">no ground truth</td></tr>";
      continue;
    }
    const AttentionScores& s = *run.attention;
    html += "<td>" + std::to_string(s.objects) + "</td><td>" + std::to_string(s.attended) +
            "</td><td>" + HtmlNumber(s.coverage) + "</td><td>" + HtmlNumber(s.mean_latency, 2) + "</td><td>" +
            std::to_string(s.revisits) + "</td><td>" + std::to_string(s.identity_switches) +
            "</td><td>" + HtmlNumber(s.mean_iou) + "</td></tr>";
  }
  return html +
         "</table><p class=\"small\">As <code>attend eval</code> scores them (SPEC 4, "
         "docs/ATTENTION.md).</p></section>\n";
}

std::string ConfigTable(const ReportInput& input) {
  std::string html = "<section><h2>Configuration differences</h2>";
  if (input.comparisons.empty()) {
    return html + "<p>One run: nothing to compare. Its configuration has " +
           std::to_string(input.runs[0].config.size()) + " keys (RUN/config.yaml).</p></section>\n";
  }
  std::set<std::string> keys;
  for (const RunComparison& c : input.comparisons) {
    for (const ConfigDifference& d : c.config) keys.insert(d.key);
  }
  if (keys.empty()) return html + "<p>None: the runs have the same configuration.</p></section>\n";
  html += "<table><tr><th>key</th>";
  for (std::size_t i = 0; i < input.runs.size(); ++i) {
    html += "<th>" + HtmlEscape(RunLabel(input.runs[i], i)) + "</th>";
  }
  html += "</tr>";
  for (const std::string& key : keys) {
    html += "<tr><td><code>" + HtmlEscape(key) + "</code></td>";
    for (const RunData& run : input.runs) {
      const auto found = run.config.find(key);
      html += found == run.config.end() ? "<td class=\"missing\">absent</td>"
                                        : "<td><code>" + HtmlEscape(found->second) + "</code></td>";
    }
    html += "</tr>";
  }
  return html + "</table></section>\n";
}

std::string MetricsTable(const ReportInput& input) {
  if (input.comparisons.empty()) return "";
  std::string html =
      "<section><h2>Saliency and targets</h2><table><tr><th>run</th><th>common frames</th>"
      "<th>mean CC</th><th>mean SIM</th><th>mean KL</th><th>targets matched</th>"
      "<th>only in A</th><th>only in this run</th><th>same attention order</th></tr>";
  for (std::size_t i = 0; i < input.comparisons.size(); ++i) {
    const RunComparison& c = input.comparisons[i];
    int matched = 0, only_a = 0, only_b = 0;
    for (const TargetMatch& m : c.matches) {
      if (m.id_a >= 0 && m.id_b >= 0) {
        ++matched;
      } else if (m.id_a >= 0) {
        ++only_a;
      } else {
        ++only_b;
      }
    }
    const auto metric = [&c](double SaliencyMetrics::*field) {
      return c.mean_saliency ? HtmlNumber((*c.mean_saliency).*field) : std::string("&ndash;");
    };
    html += "<tr><td>" + HtmlEscape(RunLabel(input.runs[i + 1], i + 1)) + "</td><td>" +
            std::to_string(c.frames.size()) + "</td><td>" + metric(&SaliencyMetrics::cc) +
            "</td><td>" + metric(&SaliencyMetrics::sim) + "</td><td>" +
            metric(&SaliencyMetrics::kl) + "</td><td>" + std::to_string(matched) + "</td><td>" +
            std::to_string(only_a) + "</td><td>" + std::to_string(only_b) + "</td><td>" +
            (c.same_order ? "yes" : "no") + "</td></tr>";
  }
  return html +
         "</table><p class=\"small\">CC: Pearson correlation (1 identical); SIM: histogram "
         "intersection of the maps normalised to sum 1 (1 identical); KL: sum Q log(eps + "
         "Q/(P + eps)), P the map of run A (0 identical). Bylinskii et al. 2016.</p>"
         "</section>\n";
}

// The data the charts draw, as one JSON object.
nlohmann::ordered_json ChartData(const ReportInput& input) {
  nlohmann::ordered_json data;
  nlohmann::ordered_json metrics = nlohmann::ordered_json::object();
  for (const char* name : {"cc", "sim", "kl"}) {
    nlohmann::ordered_json datasets = nlohmann::ordered_json::array();
    for (std::size_t i = 0; i < input.comparisons.size(); ++i) {
      nlohmann::ordered_json points = nlohmann::ordered_json::array();
      for (const FrameComparison& f : input.comparisons[i].frames) {
        double value = std::nan("");
        if (f.saliency) {
          value = name == std::string("cc")    ? f.saliency->cc
                  : name == std::string("sim") ? f.saliency->sim
                                               : f.saliency->kl;
        }
        points.push_back({{"x", f.frame},
                          {"y", std::isfinite(value) ? nlohmann::ordered_json(value)
                                                     : nlohmann::ordered_json()}});
      }
      datasets.push_back({{"label", RunLabel(input.runs[i + 1], i + 1) + " vs A"},
                          {"data", points},
                          {"borderColor", ChartColour(i + 1)},
                          {"backgroundColor", ChartColour(i + 1)}});
    }
    metrics[name] = datasets;
  }
  data["metrics"] = metrics;

  std::vector<std::string> stages;
  for (const RunData& run : input.runs) {
    for (const auto& stage : run.mean_timings_ms) {
      if (std::find(stages.begin(), stages.end(), stage.first) == stages.end()) {
        stages.push_back(stage.first);
      }
    }
  }
  nlohmann::ordered_json timing_sets = nlohmann::ordered_json::array();
  nlohmann::ordered_json target_sets = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < input.runs.size(); ++i) {
    const RunData& run = input.runs[i];
    nlohmann::ordered_json values = nlohmann::ordered_json::array();
    for (const std::string& stage : stages) {
      const auto found = std::find_if(run.mean_timings_ms.begin(), run.mean_timings_ms.end(),
                                      [&](const auto& s) { return s.first == stage; });
      values.push_back(found == run.mean_timings_ms.end() ? nlohmann::ordered_json()
                                                          : nlohmann::ordered_json(found->second));
    }
    timing_sets.push_back(
        {{"label", RunLabel(run, i)}, {"data", values}, {"backgroundColor", ChartColour(i)}});
    nlohmann::ordered_json points = nlohmann::ordered_json::array();
    for (const FrameRecord& record : run.frames) {
      points.push_back({{"x", record.frame}, {"y", VisibleTargets(record)}});
    }
    target_sets.push_back({{"label", RunLabel(run, i)},
                           {"data", points},
                           {"borderColor", ChartColour(i)},
                           {"backgroundColor", ChartColour(i)}});
  }
  data["stages"] = stages;
  data["timings"] = timing_sets;
  data["targets"] = target_sets;
  return data;
}

// Whether comparison metric `field` has a value in some frame.
bool HasMetric(const ReportInput& input, double SaliencyMetrics::*field) {
  for (const RunComparison& c : input.comparisons) {
    for (const FrameComparison& f : c.frames) {
      if (f.saliency && std::isfinite((*f.saliency).*field)) return true;
    }
  }
  return false;
}

// The charts that have data; one without is left out, not drawn empty.
std::string Charts(const ReportInput& input) {
  if (!input.chart.found()) return "";
  std::string figures;
  const auto figure = [&figures](const std::string& id, const std::string& caption) {
    figures += "<figure><canvas id=\"" + id +
               "\" width=\"560\" height=\"260\"></canvas><figcaption>" + caption +
               "</figcaption></figure>";
  };
  if (HasMetric(input, &SaliencyMetrics::cc)) figure("chart-cc", "CC per frame (1: identical)");
  if (HasMetric(input, &SaliencyMetrics::sim)) figure("chart-sim", "SIM per frame (1: identical)");
  if (HasMetric(input, &SaliencyMetrics::kl)) figure("chart-kl", "KL per frame (0: identical)");
  bool timings = false, targets = false;
  for (const RunData& run : input.runs) {
    timings = timings || !run.mean_timings_ms.empty();
    for (const FrameRecord& record : run.frames) targets = targets || VisibleTargets(record) > 0;
  }
  if (timings) figure("chart-timings", "Mean milliseconds a frame per stage");
  if (targets) figure("chart-targets", "Targets new or tracked per frame");
  if (figures.empty()) return "";
  const std::string drawing = R"JS(
function lineChart(id, datasets, label) {
  const canvas = document.getElementById(id);
  if (!canvas) return;
  new Chart(canvas, {type: 'line', data: {datasets: datasets},
    options: {spanGaps: false, elements: {point: {radius: 2}},
      scales: {x: {type: 'linear', ticks: {precision: 0}, title: {display: true, text: 'frame'}},
               y: {title: {display: true, text: label}}}}});
}
lineChart('chart-cc', DATA.metrics.cc, 'CC');
lineChart('chart-sim', DATA.metrics.sim, 'SIM');
lineChart('chart-kl', DATA.metrics.kl, 'KL');
lineChart('chart-targets', DATA.targets, 'targets');
const timings = document.getElementById('chart-timings');
if (timings) {
  new Chart(timings, {type: 'bar', data: {labels: DATA.stages, datasets: DATA.timings},
    options: {scales: {y: {title: {display: true, text: 'ms'}}}}});
})JS";
  return "<section><h2>Charts</h2><div class=\"charts\">" + figures + "</div></section>\n" +
         ChartScripts(input.chart, JsonText(ChartData(input)), drawing);
}

std::vector<int> SpreadFrames(const RunData& run, int count) {
  std::vector<int> frames;
  const int n = static_cast<int>(run.frames.size());
  for (int i = 0; i < std::min(count, n); ++i) {
    const int index = count == 1 || n == 1 ? 0 : i * (n - 1) / (std::min(count, n) - 1);
    if (frames.empty() || frames.back() != run.frames[index].frame) {
      frames.push_back(run.frames[index].frame);
    }
  }
  return frames;
}

std::string Thumbnails(const ReportInput& input) {
  std::string html = "<section><h2>Frames</h2>";
  const int width = input.thumbnail_width;
  if (input.comparisons.empty()) {
    const RunData& run = input.runs[0];
    html += "<table class=\"thumbs\">";
    for (const int frame : SpreadFrames(run, input.thumbnail_frames)) {
      html += "<tr><th>frame " + std::to_string(frame) + "</th>" +
              ImageCell(Thumbnail(OverlayImage(run.dir, frame), width), "overlay") +
              ImageCell(Thumbnail(SaliencyImage(run.dir, frame), width), "saliency") + "</tr>";
    }
    return html + "</table></section>\n";
  }
  for (std::size_t i = 0; i < input.comparisons.size(); ++i) {
    const RunComparison& c = input.comparisons[i];
    const RunData& a = input.runs[0];
    const RunData& b = input.runs[i + 1];
    const std::string label_b = RunLabel(b, i + 1).substr(0, 1);
    html += "<h3>" + HtmlEscape(RunLabel(b, i + 1)) + " against A: the frames that differ most</h3>";
    html += "<table class=\"thumbs\">";
    for (const int frame : MostDifferentFrames(c, input.thumbnail_frames)) {
      std::string cc = "&ndash;";
      for (const FrameComparison& f : c.frames) {
        if (f.frame == frame && f.saliency) cc = HtmlNumber(f.saliency->cc);
      }
      html += "<tr><th>frame " + std::to_string(frame) + "<br>CC " + cc + "</th>" +
              ImageCell(Thumbnail(OverlayImage(a.dir, frame), width), "A overlay") +
              ImageCell(Thumbnail(OverlayImage(b.dir, frame), width), label_b + " overlay") +
              ImageCell(Thumbnail(SaliencyImage(a.dir, frame), width), "A saliency") +
              ImageCell(Thumbnail(SaliencyImage(b.dir, frame), width), label_b + " saliency") +
              "</tr>";
    }
    html += "</table>";
  }
  return html + "</section>\n";
}

std::string TargetRows(const std::vector<TargetSummary>& targets) {
  std::string html;
  for (const TargetSummary& t : targets) {
    html += "<tr><td>" + std::to_string(t.id) + "</td><td>" + HtmlEscape(t.kind) + "</td><td>" +
            std::to_string(t.rank + 1) + "</td><td>" + std::to_string(t.first_frame) + "</td><td>" +
            std::to_string(t.last_frame) + "</td><td>" + std::to_string(t.frames) + "</td></tr>";
  }
  return html;
}

std::string TargetTables(const ReportInput& input) {
  std::string html = "<section><h2>Targets</h2>";
  if (input.comparisons.empty()) {
    return html +
           "<table><tr><th>id</th><th>kind</th><th>attention order</th><th>first frame</th>"
           "<th>last frame</th><th>frames</th></tr>" +
           TargetRows(SummariseTargets(input.runs[0].frames)) + "</table></section>\n";
  }
  for (std::size_t i = 0; i < input.comparisons.size(); ++i) {
    const RunComparison& c = input.comparisons[i];
    const std::string b = RunLabel(input.runs[i + 1], i + 1).substr(0, 1);
    std::map<int, const TargetSummary*> in_a, in_b;
    for (const TargetSummary& t : c.targets_a) in_a[t.id] = &t;
    for (const TargetSummary& t : c.targets_b) in_b[t.id] = &t;
    html += "<h3>" + HtmlEscape(RunLabel(input.runs[i + 1], i + 1)) + " against A (attention order " +
            (c.same_order ? "the same" : "different") + ")</h3>";
    html += "<table><tr><th>A id</th><th>" + b + " id</th><th>kind</th><th>A order</th><th>" + b +
            " order</th><th>A first frame</th><th>" + b +
            " first frame</th><th>frames matched</th></tr>";
    for (const TargetMatch& m : c.matches) {
      const TargetSummary* ta = m.id_a >= 0 ? in_a[m.id_a] : nullptr;
      const TargetSummary* tb = m.id_b >= 0 ? in_b[m.id_b] : nullptr;
      const auto cell = [](const TargetSummary* t, int TargetSummary::*field, int offset) {
        return t ? "<td>" + std::to_string(t->*field + offset) + "</td>"
                 : std::string("<td class=\"missing\">&ndash;</td>");
      };
      const bool differs = ta && tb && (ta->rank != tb->rank || ta->first_frame != tb->first_frame);
      html += std::string("<tr") +
              (ta && tb ? (differs ? " class=\"changed\"" : "") : " class=\"only\"") + ">" +
              cell(ta, &TargetSummary::id, 0) + cell(tb, &TargetSummary::id, 0) + "<td>" +
              HtmlEscape(ta ? ta->kind : tb->kind) + "</td>" + cell(ta, &TargetSummary::rank, 1) +
              cell(tb, &TargetSummary::rank, 1) + cell(ta, &TargetSummary::first_frame, 0) +
              cell(tb, &TargetSummary::first_frame, 0) + "<td>" + std::to_string(m.frames_matched) +
              "</td></tr>";
    }
    html += "</table>";
  }
  return html + "</section>\n";
}

}  // namespace



std::vector<int> MostDifferentFrames(const RunComparison& comparison, int count) {
  std::vector<const FrameComparison*> frames;
  for (const FrameComparison& f : comparison.frames) frames.push_back(&f);
  const auto key = [](const FrameComparison* f) {
    // Frames without a finite CC sort by their share of matched targets, after those with one.
    if (f->saliency && std::isfinite(f->saliency->cc)) return std::make_pair(0, f->saliency->cc);
    const int targets = std::max(f->targets_a, f->targets_b);
    return std::make_pair(1, targets > 0 ? static_cast<double>(f->matched) / targets : 1.0);
  };
  std::stable_sort(frames.begin(), frames.end(),
                   [&](const auto* x, const auto* y) { return key(x) < key(y); });
  std::vector<int> out;
  for (int i = 0; i < count && i < static_cast<int>(frames.size()); ++i) {
    out.push_back(frames[i]->frame);
  }
  std::sort(out.begin(), out.end());
  return out;
}

std::string ReportHtml(const ReportInput& input) {
  const bool single = input.comparisons.empty();
  std::string html = HtmlPageStart(
      single ? "attend report" : "attend compare",
      single ? "attend report: " + HtmlEscape(input.runs[0].dir)
             : "attend compare: " + std::to_string(input.runs.size()) + " runs",
      input.command_line);
  html += Notes(input);
  html += RunsTable(input);
  html += ConfigTable(input);
  html += MetricsTable(input);
  html += AttentionTable(input);
  html += Charts(input);
  html += Thumbnails(input);
  std::vector<std::string> labels;
  for (std::size_t i = 0; i < input.runs.size(); ++i) labels.push_back(RunLabel(input.runs[i], i));
  html += DepthSectionHtml(input.runs, input.comparisons, labels);
  html += TargetTables(input);
  html += HtmlPageEnd();
  return html;
}

}  // namespace attend
