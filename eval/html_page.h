// The pieces every attend HTML report shares (attend report, attend compare, attend sweep
// --collect; docs/COMPARE.md, docs/SWEEPS.md): one self-contained page, its style, escaping,
// numbers, notes, sortable tables and the Chart.js library of Debian inlined, so that a page
// opens offline from a file.
#pragma once

#include <string>
#include <vector>

namespace attend {

// `text` with & < > " ' escaped: safe as element text and as a quoted attribute value.
std::string HtmlEscape(const std::string& text);

// `text` safe inside a <script> element: no "</" that could close it. For trusted code (the
// chart library); data goes through ScriptJson.
std::string ScriptSafe(const std::string& text);

// JSON text that can stand inside a <script> element whatever its strings hold: < > & and the
// line separators U+2028 and U+2029 written as \u escapes (they occur only inside strings), so
// that no "</script", "<!--" or "<script" from a run's name or configuration can change the
// page's structure (HTML5's script-data states).
std::string ScriptJson(const std::string& json);

// A table cell's number: `digits` decimals, "&ndash;" when not finite, no "-0.000".
std::string HtmlNumber(double value, int digits = 3);

// The colour of series `i` in charts.
const char* ChartColour(std::size_t i);

// Where the Chart.js library of Debian's libjs-chart.js is, "" when it is not installed.
std::string FindChartJs();

// The Chart.js library's source for inlining.
struct ChartLibrary {
  std::string source;  // "" when not found
  std::string path;    // where it was read, or where it was looked for
  bool found() const { return !source.empty(); }
};
ChartLibrary LoadChartLibrary();

// The note a page gives when Chart.js is missing: the charts are left out.
std::string ChartLibraryMissingNote(const ChartLibrary& library);

// RFC 4648 base64 of `bytes`.
std::string Base64(const std::vector<unsigned char>& bytes);

// The page's start: doctype, title, the shared style, the heading (HTML) and the command line
// that wrote it.
std::string HtmlPageStart(const std::string& title, const std::string& heading_html,
                          const std::string& command_line);
// The page's end.
std::string HtmlPageEnd();

// A "Notes" section listing `notes`; "" when there are none.
std::string HtmlNotes(const std::vector<std::string>& notes);

// The script that makes every <table class="sortable"> sortable by a click on a column's
// heading (numbers as numbers, empty cells last). Include once per page.
std::string SortableTablesScript();

// Chart.js inlined, then `data_json` as the constant DATA, then `drawing` (JavaScript that
// draws from DATA). "" when the library is missing.
std::string ChartScripts(const ChartLibrary& library, const std::string& data_json,
                         const std::string& drawing);

}  // namespace attend
