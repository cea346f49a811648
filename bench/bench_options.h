// The command line shared by the benchmarks (parsed with CLI11):
//   NAME [--data DIR] [--home DIR] [--repeat N] [--markdown FILE]
#pragma once

#include <CLI/CLI.hpp>
#include <string>

namespace attend::bench {

struct BenchOptions {
  std::string data_dir;       // reference data (middlebury/, otb/, ...); missing parts skipped
  std::string home;           // the attend source tree, for sequences/*.yaml
  int repeat = 7;             // timed rounds after one warm-up round
  std::string markdown_path;  // also write the report here
  std::string command_line;   // as invoked, for the report
};

// Parses argv into `options`, whose values on entry are the defaults. Returns -1 to go on, or
// the exit status to return: 0 after --help, 2 after a bad command line.
inline int ParseBenchOptions(const std::string& name, const std::string& description,
                             const std::string& data_help, int argc, char** argv,
                             BenchOptions* options) {
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  return -1;
}

}  // namespace attend::bench
