#include "eval/sweep_report.h"

#include <cmath>
#include <nlohmann/json.hpp>
#include <set>

#include "util/json_text.h"
#include "util/strings.h"

namespace attend {

namespace {

using Json = nlohmann::ordered_json;

// Scores whose keys end in or contain these words are better low.
bool EndsWith(const std::string& text, const std::string& end) {
  return text.size() >= end.size() && text.compare(text.size() - end.size(), end.size(), end) == 0;
}

std::string LastPart(const std::string& name) {
  const std::size_t dot = name.rfind('.');
  return dot == std::string::npos ? name : name.substr(dot + 1);
}

// Fields a scorer reports beside its scores that describe the input, not the result: left out
// of the best configurations and the plots (sweep.csv keeps them).
bool IsContext(const std::string& name) {
  static const std::vector<std::string> context = {"frames", "objects", "match_iou", "GT",
                                                   "ignored", "images", "rows"};
  return std::find(context.begin(), context.end(), LastPart(name)) != context.end();
}

bool HasValue(const SweepReportCell& cell, const std::string& score) {
  const auto found = cell.scores.find(score);
  return found != cell.scores.end() && std::isfinite(found->second);
}

std::string SettingsText(const std::vector<std::string>& keys,
                         const std::vector<std::string>& settings) {
  std::vector<std::string> parts;
  for (std::size_t k = 0; k < keys.size(); ++k) parts.push_back(keys[k] + "=" + settings[k]);
  return parts.empty() ? "(the base configuration)" : Join(parts, ", ");
}

// The mean of `score` over the done cells of each configuration (distinct settings), in sweep
// order; configurations without a value are left out.
std::vector<std::pair<std::vector<std::string>, std::pair<double, int>>> ConfigurationMeans(
    const SweepReportInput& input, const std::string& score) {
  std::vector<std::pair<std::vector<std::string>, std::pair<double, int>>> means;
  for (const SweepReportCell& cell : input.cells) {
    if (cell.state != "done" || !HasValue(cell, score)) continue;
    auto found = std::find_if(means.begin(), means.end(),
                              [&](const auto& m) { return m.first == cell.settings; });
    if (found == means.end()) {
      means.push_back({cell.settings, {0.0, 0}});
      found = means.end() - 1;
    }
    found->second.first += cell.scores.at(score);
    ++found->second.second;
  }
  for (auto& mean : means) mean.second.first /= mean.second.second;
  return means;
}

// The scores worth comparing: not context, and not the same for every configuration.
std::vector<std::string> ComparedScores(const SweepReportInput& input) {
  std::vector<std::string> compared;
  for (const std::string& score : input.scores) {
    if (IsContext(score)) continue;
    const auto means = ConfigurationMeans(input, score);
    bool varies = false;
    for (const auto& mean : means) {
      varies = varies || std::abs(mean.second.first - means[0].second.first) >
                             1e-12 * std::max(1.0, std::abs(means[0].second.first));
    }
    if (varies) compared.push_back(score);
  }
  return compared;
}

std::string CellsTable(const SweepReportInput& input) {
  std::string html =
      "<section><h2>Cells</h2><p class=\"small\">Click a heading to sort by it.</p>"
      "<table class=\"sortable\"><tr><th>cell</th><th>input</th>";
  for (const std::string& key : input.keys) html += "<th><code>" + HtmlEscape(key) + "</code></th>";
  html += "<th>state</th><th>seconds</th>";
  for (const std::string& score : input.scores) {
    html += "<th>" + HtmlEscape(score) + (LowerIsBetter(score) ? " &darr;" : " &uarr;") + "</th>";
  }
  html += "</tr>";
  for (const SweepReportCell& cell : input.cells) {
    html += std::string("<tr") + (cell.state == "done" ? "" : " class=\"failed\"") + "><td>" +
            HtmlEscape(cell.name) + "</td><td>" + HtmlEscape(cell.input) + "</td>";
    for (const std::string& value : cell.settings) {
      html += "<td><code>" + HtmlEscape(value) + "</code></td>";
    }
    html += "<td" + (cell.message.empty() ? std::string() : " title=\"" + HtmlEscape(cell.message) + "\"") +
            ">" + HtmlEscape(cell.state) + "</td><td class=\"num\">" +
            HtmlNumber(cell.state == "waiting" ? std::nan("") : cell.seconds, 1) + "</td>";
    for (const std::string& score : input.scores) {
      const auto found = cell.scores.find(score);
      const double value = found == cell.scores.end() ? std::nan("") : found->second;
      html += "<td class=\"num\">" + (std::isfinite(value) ? HtmlNumber(value, 4) : "") + "</td>";
    }
    html += "</tr>";
  }
  html += "</table>";
  std::string failed;
  for (const SweepReportCell& cell : input.cells) {
    if (cell.state == "failed" || cell.state == "killed") {
      failed += "<li><code>" + HtmlEscape(cell.name) + "</code>: " + HtmlEscape(cell.state) +
                ": " + HtmlEscape(cell.message) + "</li>";
    }
  }
  if (!failed.empty()) html += "<p>Cells without scores:</p><ul class=\"notes\">" + failed + "</ul>";
  return html + "</section>\n";
}

std::string BestTable(const SweepReportInput& input) {
  const std::vector<BestConfiguration> best = BestConfigurations(input);
  if (best.empty()) return "";
  std::string html =
      "<section><h2>Best configuration per score</h2><p class=\"small\">For each score that differs between "
      "configurations, the configuration whose mean over its inputs is best (&uarr; higher is better, &darr; lower). Its settings follow, "
      "as a <code>set:</code> block and as <code>--set</code> words; the effective configuration "
      "is in each cell's <code>config.yaml</code>.</p><table class=\"sortable\"><tr><th>score</th>"
      "<th>best</th><th>mean</th><th>inputs</th><th>settings</th></tr>";
  std::vector<std::vector<std::string>> shown;
  for (const BestConfiguration& b : best) {
    html += "<tr><td>" + HtmlEscape(b.score) + "</td><td>" +
            (LowerIsBetter(b.score) ? "lowest" : "highest") + "</td><td class=\"num\">" +
            HtmlNumber(b.mean, 4) + "</td><td class=\"num\">" + std::to_string(b.cells) +
            "</td><td><code>" + HtmlEscape(SettingsText(input.keys, b.settings)) + "</code></td></tr>";
    if (std::find(shown.begin(), shown.end(), b.settings) == shown.end()) {
      shown.push_back(b.settings);
    }
  }
  html += "</table>";
  for (const std::vector<std::string>& settings : shown) {
    std::vector<std::string> best_of;
    for (const BestConfiguration& b : best) {
      if (b.settings == settings) best_of.push_back(b.score);
    }
    const SweepReportCell* example = nullptr;
    for (const SweepReportCell& cell : input.cells) {
      if (cell.settings == settings) example = example == nullptr ? &cell : example;
    }
    std::string yaml = "set:\n";
    for (std::size_t k = 0; k < input.keys.size(); ++k) {
      yaml += "  " + input.keys[k] + ": " + settings[k] + "\n";
    }
    std::string words;
    if (example != nullptr) {
      if (!example->config.empty()) words += " --config " + example->config;
      for (const std::string& set : example->sets) words += " --set '" + set + "'";
    }
    html += "<h3>" + HtmlEscape(SettingsText(input.keys, settings)) + "</h3><p class=\"small\">Best for " +
            HtmlEscape(Join(best_of, ", ")) + "</p><pre>" + HtmlEscape(yaml) + "</pre><pre>" +
            HtmlEscape("attend " + input.command + words) + "</pre>";
    if (example != nullptr && !example->config_yaml.empty()) {
      html += "<details><summary>Effective configuration (" + HtmlEscape(example->name) +
              "/config.yaml)</summary><pre>" + HtmlEscape(example->config_yaml) + "</pre></details>";
    }
  }
  return html + "</section>\n";
}

// Draws DATA's plots (PlotData) with Chart.js: for the chosen score and inputs, the mean of
// each group's values with its standard deviation band and its range.
constexpr const char* kDrawPlots = R"JS(
const charts = [];
function summary(score, group, input) {
  return group.values.map(function (tuple) {
    const ys = DATA.cells.filter(function (c) {
        return group.keys.every(function (k, i) { return c.settings[k] === tuple[i]; }) &&
               (input === '' || c.input === input); })
      .map(function (c) { return c.scores[score]; })
      .filter(function (y) { return y !== null; });
    if (ys.length === 0) return {mean: null, sd: null, min: null, max: null};
    const mean = ys.reduce(function (a, b) { return a + b; }, 0) / ys.length;
    const sd = Math.sqrt(ys.reduce(function (a, y) { return a + (y - mean) * (y - mean); }, 0) / ys.length);
    return {mean: mean, sd: sd, min: Math.min.apply(null, ys), max: Math.max.apply(null, ys)};
  });
}
function draw() {
  const score = DATA.scores[document.getElementById('score').value];
  const input = document.getElementById('input').value;
  charts.forEach(function (c) { c.destroy(); });
  charts.length = 0;
  DATA.groups.forEach(function (group, k) {
    const s = summary(score, group, input);
    charts.push(new Chart(document.getElementById('plot-' + k), {type: 'line',
      data: {labels: group.labels, datasets: [
        {label: 'mean + sd', data: s.map(function (p) { return p.mean === null ? null : p.mean + p.sd; }),
         borderWidth: 0, pointRadius: 0, backgroundColor: 'rgba(31,119,180,0.15)', fill: '+1'},
        {label: 'mean - sd', data: s.map(function (p) { return p.mean === null ? null : p.mean - p.sd; }),
         borderWidth: 0, pointRadius: 0, fill: false},
        {label: 'mean', data: s.map(function (p) { return p.mean; }), borderColor: '#1f77b4',
         backgroundColor: '#1f77b4'},
        {label: 'max', data: s.map(function (p) { return p.max; }), borderColor: '#999',
         borderDash: [4, 4], pointRadius: 0, borderWidth: 1},
        {label: 'min', data: s.map(function (p) { return p.min; }), borderColor: '#999',
         borderDash: [4, 4], pointRadius: 0, borderWidth: 1}]},
      options: {plugins: {legend: {labels: {filter: function (item) { return item.text === 'mean'; }}}},
        scales: {x: {title: {display: true, text: group.label}},
                 y: {title: {display: true, text: score}}}}}));
  });
}
document.getElementById('score').addEventListener('change', draw);
document.getElementById('input').addEventListener('change', draw);
draw();)JS";

// The groups of keys plotted together: each zip group, each grid key alone.
std::vector<std::vector<int>> PlotGroups(const SweepReportInput& input) {
  std::vector<std::vector<int>> groups = input.groups;
  if (groups.empty()) {
    for (std::size_t k = 0; k < input.keys.size(); ++k) groups.push_back({static_cast<int>(k)});
  }
  return groups;
}

// What the page's script draws: each group's distinct tuples of values, the plotted scores and
// the done cells' settings and scores.
Json PlotData(const SweepReportInput& input, const std::vector<std::vector<int>>& groups,
              const std::vector<std::string>& plotted) {
  Json data;
  Json group_json = Json::array();
  for (const std::vector<int>& group : groups) {
    std::vector<std::vector<std::string>> seen;
    std::vector<std::string> labels, names;
    for (const SweepReportCell& cell : input.cells) {
      std::vector<std::string> tuple;
      for (const int k : group) tuple.push_back(cell.settings[k]);
      if (std::find(seen.begin(), seen.end(), tuple) == seen.end()) {
        seen.push_back(tuple);
        labels.push_back(Join(tuple, " / "));
      }
    }
    for (const int k : group) names.push_back(input.keys[k]);
    group_json.push_back({{"label", Join(names, " / ")}, {"keys", group}, {"values", seen},
                          {"labels", labels}});
  }
  data["groups"] = group_json;
  data["scores"] = plotted;
  Json cells = Json::array();
  for (const SweepReportCell& cell : input.cells) {
    if (cell.state != "done") continue;
    Json scores = Json::object();
    for (const std::string& score : plotted) {
      scores[score] = HasValue(cell, score) ? Json(cell.scores.at(score)) : Json();
    }
    cells.push_back({{"input", cell.input}, {"settings", cell.settings}, {"scores", scores}});
  }
  data["cells"] = cells;
  return data;
}

// The plots' section: a choice of score and of inputs, and a canvas a group.
std::string PlotSection(const SweepReportInput& input, const std::vector<std::vector<int>>& groups,
                        const std::vector<std::string>& plotted) {
  std::vector<std::string> inputs;
  for (const SweepReportCell& cell : input.cells) {
    if (std::find(inputs.begin(), inputs.end(), cell.input) == inputs.end()) {
      inputs.push_back(cell.input);
    }
  }
  std::string html =
      "<section><h2>Scores against the swept parameters</h2><p>Score: <select id=\"score\">";
  for (std::size_t s = 0; s < plotted.size(); ++s) {
    html += "<option value=\"" + std::to_string(s) + "\">" + HtmlEscape(plotted[s]) + "</option>";
  }
  html += "</select> Inputs: <select id=\"input\"><option value=\"\">all</option>";
  for (const std::string& name : inputs) {
    html += "<option value=\"" + HtmlEscape(name) + "\">" + HtmlEscape(name) + "</option>";
  }
  html +=
      "</select></p><p class=\"small\">For each value of a parameter: the mean of the score over "
      "the done cells with that value (the inputs chosen and every value of the other "
      "parameters), with the band of one standard deviation and the range (dashed).</p>"
      "<div class=\"charts\">";
  for (std::size_t g = 0; g < groups.size(); ++g) {
    std::vector<std::string> names;
    for (const int k : groups[g]) names.push_back(input.keys[k]);
    html += "<figure><canvas id=\"plot-" + std::to_string(g) +
            "\" width=\"460\" height=\"260\"></canvas><figcaption><code>" +
            HtmlEscape(Join(names, " / ")) + "</code>" +
            (groups[g].size() > 1 ? " (zipped: changed together)" : "") +
            "</figcaption></figure>";
  }
  return html + "</div></section>\n";
}

// Each score against each swept key: the data, drawn by the page's script.
std::string Plots(const SweepReportInput& input, std::vector<std::string>* notes) {
  if (input.keys.empty()) return "";
  std::vector<std::string> plotted = ComparedScores(input);
  // The headline score of each scorer is shown first.
  for (const char* headline : {"coverage", "success_auc", "nss"}) {
    const auto found = std::find(plotted.begin(), plotted.end(), headline);
    if (found != plotted.end()) std::rotate(plotted.begin(), found, found + 1);
  }
  if (plotted.empty()) return "";
  if (!input.chart.found()) {
    notes->push_back(ChartLibraryMissingNote(input.chart));
    return "";
  }
  const std::vector<std::vector<int>> groups = PlotGroups(input);
  return PlotSection(input, groups, plotted) +
         ChartScripts(input.chart, JsonText(PlotData(input, groups, plotted)), kDrawPlots);
}

}  // namespace

bool LowerIsBetter(const std::string& name) {
  const std::string last = Lowercase(LastPart(name));
  static const std::vector<std::string> lower = {
      "mean_latency", "revisits", "identity_switches", "idfp", "idfn", "fp", "fn", "idsw",
      "ml", "frag", "mean_bad1", "mean_bad2", "kl", "ms_per_frame", "seconds",
      "targets_started", "ids_per_attended_object",
      // attend eval's landing block (eval/landing.h): attention off the objects, depth errors.
      "on_sky", "on_ground", "without_depth", "elsewhere", "on_sky_share", "on_ground_share",
      "without_depth_share", "elsewhere_share", "median_relative_error", "median_abs_error_m"};
  return std::find(lower.begin(), lower.end(), last) != lower.end() || EndsWith(last, "_ms");
}

std::vector<BestConfiguration> BestConfigurations(const SweepReportInput& input) {
  std::vector<BestConfiguration> best;
  for (const std::string& score : ComparedScores(input)) {
    BestConfiguration winner;
    winner.score = score;
    bool any = false;
    for (const auto& [settings, mean] : ConfigurationMeans(input, score)) {
      const bool better = !any || (LowerIsBetter(score) ? mean.first < winner.mean
                                                         : mean.first > winner.mean);
      if (better) {
        winner.settings = settings;
        winner.mean = mean.first;
        winner.cells = mean.second;
        any = true;
      }
    }
    if (any) best.push_back(std::move(winner));
  }
  return best;
}

std::string SweepReportHtml(const SweepReportInput& input) {
  int done = 0;
  for (const SweepReportCell& cell : input.cells) done += cell.state == "done" ? 1 : 0;
  std::vector<std::string> notes = input.notes;
  const std::string plots = Plots(input, &notes);
  std::string html = HtmlPageStart(
      "attend sweep", "attend sweep: " + HtmlEscape(input.dir), input.command_line);
  html += "<p>" + std::to_string(input.cells.size()) + " cells (" + std::to_string(done) +
          " done) of <code>attend " + HtmlEscape(input.command) + "</code> over " +
          std::to_string(input.keys.size()) + " swept keys; the scores of each cell are in " +
          "<code>sweep.csv</code>.</p>\n";
  html += HtmlNotes(notes);
  html += plots;
  html += CellsTable(input);
  html += BestTable(input);
  html += SortableTablesScript();
  html += HtmlPageEnd();
  return html;
}

}  // namespace attend
