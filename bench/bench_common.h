// What the benchmarks share: their command line (parsed with CLI11),
//   NAME [--data DIR] [--home DIR] [--repeat N] [--markdown FILE]
// and the helpers of their markdown reports.
#pragma once

#include <CLI/CLI.hpp>
#include <algorithm>
#include <ctime>
#include <fstream>
#include <string>
#include <vector>

#include "util/strings.h"

namespace attend::bench {

struct BenchOptions {
  std::string data_dir;       // reference data (middlebury/, otb/, ...); missing parts skipped
  std::string home;           // the attend source tree, for sequences/*.yaml
  int repeat = 7;             // timed rounds after one warm-up round
  std::string markdown_path;  // also write the report here
  std::string command_line;   // as invoked, for the report
  std::string sequences;      // --sequences: a bench's own filter (only where it offers one)
};

// Parses argv into `options`, whose values on entry are the defaults. Returns -1 to go on, or
// the exit status to return: 0 after --help, 2 after a bad command line. A bench that can run
// a subset of its inputs passes `sequences_help` to offer --sequences LIST.
inline int ParseBenchOptions(const std::string& name, const std::string& description,
                             const std::string& data_help, int argc, char** argv,
                             BenchOptions* options, const std::string& sequences_help = "") {
  options->command_line = name;
  for (int i = 1; i < argc; ++i) options->command_line += std::string(" ") + argv[i];
  CLI::App app{description, name};
  app.add_option("--data", options->data_dir, data_help)->capture_default_str();
  app.add_option("--home", options->home, "attend source tree, for sequences/*.yaml")
      ->capture_default_str();
  app.add_option("--repeat", options->repeat, "timed rounds after one warm-up round")
      ->check(CLI::Range(1, 10000))
      ->capture_default_str();
  app.add_option("--markdown", options->markdown_path, "also write the report to FILE");
  if (!sequences_help.empty()) app.add_option("--sequences", options->sequences, sequences_help);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  return -1;
}

using attend::Fixed;  // util/strings.h

// The median of `values` (the mean of the middle two for an even count); 0 when empty.
inline double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const size_t half = values.size() / 2;
  return values.size() % 2 == 1 ? values[half] : 0.5 * (values[half - 1] + values[half]);
}

// The processor's model name from /proc/cpuinfo, or "unknown".
inline std::string CpuModel() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpuinfo, line)) {
    if (line.rfind("model name", 0) == 0) {
      const size_t colon = line.find(':');
      if (colon != std::string::npos) return line.substr(colon + 2);
    }
  }
  return "unknown";
}

// "YYYY-mm-dd HH:MM UTC", now.
inline std::string UtcNow() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char buffer[32];
  std::strftime(buffer, sizeof(buffer), "%Y-%m-%d %H:%M UTC", &utc);
  return buffer;
}

}  // namespace attend::bench
