#include "cli/cli_options.h"

#include <cmath>

#include <filesystem>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "util/error.h"
#include "util/timer.h"

namespace attend {

CLI::Validator FiniteRange(double min, double max) {
  const CLI::Range range(min, max);
  return CLI::Validator(
      [range](std::string& text) {
        double value = 0.0;
        if (CLI::detail::lexical_cast(text, value) && !std::isfinite(value)) {
          return "'" + text + "' is not a finite number";
        }
        std::string copy = text;
        return range(copy);
      },
      range.get_description());
}

CLI::Option* AddSetOption(CLI::App* command, std::vector<std::string>* sets,
                          const std::string& help) {
  return command->add_option("--set", *sets, help)
      ->type_name("KEY=VALUE")
      ->expected(1)
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
}

void PrintRunProgress(const RunProgress& progress) {
  // Ten updates a second are enough to read; more would slow a fast run down.
  static Stopwatch since_last;
  const bool last = progress.total > 0 && progress.done == progress.total;
  if (progress.done > 1 && !last && since_last.ElapsedMs() < 100.0) return;
  since_last.Restart();
  std::ostringstream line;
  line << "\r[attend] frame " << progress.done;
  if (progress.total > 0) line << "/" << progress.total;
  line << std::fixed << std::setprecision(1) << "  " << progress.fps << " frames/s";
  if (progress.total > 0 && progress.fps > 0) {
    line << "  ETA " << std::setprecision(0) << (progress.total - progress.done) / progress.fps
         << " s";
  }
  line << "   ";
  std::cerr << line.str() << std::flush;
}

std::vector<std::string> OutputStems(const std::vector<std::string>& images,
                                     const std::string& outputs) {
  std::map<std::string, std::string> path_of_stem;
  std::vector<std::string> stems;
  for (const std::string& image : images) {
    const std::string stem = std::filesystem::path(image).stem().string();
    const auto [it, inserted] = path_of_stem.emplace(stem, image);
    if (!inserted) {
      std::string named = outputs;
      for (size_t at = named.find("STEM"); at != std::string::npos; at = named.find("STEM")) {
        named.replace(at, 4, stem);
      }
      throw ConfigError("images " + it->second + " and " + image + " have the same stem '" + stem +
                        "': their " + named + " would overwrite each other");
    }
    stems.push_back(stem);
  }
  return stems;
}

}  // namespace attend
