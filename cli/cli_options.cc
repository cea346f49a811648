#include "cli/cli_options.h"

#include <filesystem>
#include <map>
#include <stdexcept>

#include "util/error.h"

namespace attend {

CLI::Option* AddSetOption(CLI::App* command, std::vector<std::string>* sets,
                          const std::string& help) {
  return command->add_option("--set", *sets, help)
      ->type_name("KEY=VALUE")
      ->expected(1)
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
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
