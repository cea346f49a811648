#include "eval/html_page.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "util/strings.h"

namespace attend {

namespace {

constexpr const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e",
                                    "#9467bd", "#8c564b", "#e377c2", "#17becf"};

constexpr const char* kStyle = R"CSS(<style>
body { font-family: sans-serif; margin: 1.5em; color: #222; background: #fff; }
h1 { font-size: 1.5em; } h2 { border-bottom: 1px solid #ccc; margin-top: 1.5em; }
table { border-collapse: collapse; margin: 0.5em 0; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.6em; text-align: left; vertical-align: top; }
th { background: #f0f0f0; }
table.sortable th { cursor: pointer; } table.sortable th:hover { background: #e2e8f0; }
td.missing { color: #999; font-style: italic; } td.num { text-align: right; }
tr.changed td { background: #fff4d6; } tr.only td { background: #fde2e2; }
tr.failed td { background: #fde2e2; } td.best { font-weight: bold; background: #e3f4e1; }
.charts { display: flex; flex-wrap: wrap; gap: 1em; }
figure { margin: 0; } figcaption { font-size: 0.9em; color: #555; }
.thumbs img { display: block; }
pre { background: #f6f6f6; padding: 0.5em; overflow-x: auto; }
.small { font-size: 0.85em; color: #555; } ul.notes li { color: #a33; }
</style>
)CSS";

}  // namespace

std::string HtmlEscape(const std::string& text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string ScriptSafe(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '<' && i + 1 < text.size() && text[i + 1] == '/') {
      out += "<\\/";
      ++i;
    } else {
      out += text[i];
    }
  }
  return out;
}

std::string ScriptJson(const std::string& json) {
  std::string out;
  out.reserve(json.size());
  for (std::size_t i = 0; i < json.size(); ++i) {
    const char c = json[i];
    if (c == '<') {
      out += "\\u003c";
    } else if (c == '>') {
      out += "\\u003e";
    } else if (c == '&') {
      out += "\\u0026";
    } else if (c == '\xE2' && i + 2 < json.size() && json[i + 1] == '\x80' &&
               (json[i + 2] == '\xA8' || json[i + 2] == '\xA9')) {
      out += json[i + 2] == '\xA8' ? "\\u2028" : "\\u2029";
      i += 2;
    } else {
      out += c;
    }
  }
  return out;
}

std::string HtmlNumber(double value, int digits) {
  if (!std::isfinite(value)) return "&ndash;";
  if (std::abs(value) < 0.5 * std::pow(10.0, -digits)) value = 0.0;
  return Fixed(value, digits);
}

const char* ChartColour(std::size_t i) {
  return kPalette[i % (sizeof(kPalette) / sizeof(*kPalette))];
}

std::string FindChartJs() {
  for (const char* path :
       {"/usr/share/javascript/chart.js/chart.min.js",
        "/usr/share/javascript/chart.js/Chart.min.js", "/usr/share/javascript/chart.js/chart.js"}) {
    std::error_code error;
    if (std::filesystem::is_regular_file(path, error)) return path;
  }
  return "";
}

ChartLibrary LoadChartLibrary() {
  ChartLibrary library;
  const std::string path = FindChartJs();
  if (path.empty()) {
    library.path = "looked for /usr/share/javascript/chart.js/chart.min.js";
    return library;
  }
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  library.source = text.str();
  library.path = path;
  return library;
}

std::string ChartLibraryMissingNote(const ChartLibrary& library) {
  return "Chart.js was not found (" + library.path +
         "; Debian package libjs-chart.js): the charts are left out, the tables are complete";
}

std::string Base64(const std::vector<unsigned char>& bytes) {
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  std::size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const unsigned v = (bytes[i] << 16) | (bytes[i + 1] << 8) | bytes[i + 2];
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += kAlphabet[v & 63];
  }
  if (i + 1 == bytes.size()) {
    const unsigned v = bytes[i] << 16;
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += "==";
  } else if (i + 2 == bytes.size()) {
    const unsigned v = (bytes[i] << 16) | (bytes[i + 1] << 8);
    out += kAlphabet[(v >> 18) & 63];
    out += kAlphabet[(v >> 12) & 63];
    out += kAlphabet[(v >> 6) & 63];
    out += '=';
  }
  return out;
}

std::string HtmlPageStart(const std::string& title, const std::string& heading_html,
                          const std::string& command_line) {
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\n<title>" +
         HtmlEscape(title) + "</title>\n" + kStyle + "</head><body>\n<h1>" + heading_html +
         "</h1>\n<p class=\"small\"><code>" + HtmlEscape(command_line) + "</code></p>\n";
}

std::string HtmlPageEnd() { return "</body></html>\n"; }

std::string HtmlNotes(const std::vector<std::string>& notes) {
  if (notes.empty()) return "";
  std::string html = "<section><h2>Notes</h2><ul class=\"notes\">";
  for (const std::string& note : notes) html += "<li>" + HtmlEscape(note) + "</li>";
  return html + "</ul></section>\n";
}

std::string SortableTablesScript() {
  return R"JS(<script>
document.querySelectorAll('table.sortable').forEach(function (table) {
  const headings = table.querySelectorAll('tr:first-child th');
  headings.forEach(function (th, column) {
    th.title = 'Sort by this column';
    th.addEventListener('click', function () {
      const rows = Array.from(table.querySelectorAll('tr')).slice(1);
      const up = th.dataset.order !== 'up';
      headings.forEach(function (h) { delete h.dataset.order; });
      th.dataset.order = up ? 'up' : 'down';
      const key = function (row) {
        const cell = row.children[column];
        const text = cell ? (cell.dataset.value !== undefined ? cell.dataset.value : cell.textContent) : '';
        const number = parseFloat(text);
        return {empty: text.trim() === '' || text === '\u2013', number: number, text: text,
                numeric: !isNaN(number) && isFinite(text)};
      };
      rows.sort(function (a, b) {
        const x = key(a), y = key(b);
        if (x.empty !== y.empty) return x.empty ? 1 : -1;
        const order = x.numeric && y.numeric ? x.number - y.number : x.text.localeCompare(y.text);
        return up ? order : -order;
      });
      rows.forEach(function (row) { row.parentNode.appendChild(row); });
    });
  });
});
</script>
)JS";
}

std::string ChartScripts(const ChartLibrary& library, const std::string& data_json,
                         const std::string& drawing) {
  if (!library.found()) return "";
  return "<script>\n" + ScriptSafe(library.source) + "\n</script>\n<script>\nconst DATA = " +
         ScriptJson(data_json) + ";\nChart.defaults.animation = false;\n"
         "Chart.defaults.responsive = false;\n" + drawing + "\n</script>\n";
}

}  // namespace attend
