// attend options-doc: the option tables of configs/README.md, generated from the options
// structs' field tables (pipeline/options_doc.h).
#include <iostream>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "pipeline/options_doc.h"

namespace attend {

namespace {

struct OptionsDocArguments {
  std::string write;
  std::string section;
};

int OptionsDoc(const OptionsDocArguments& args) {
  if (!args.write.empty()) {
    const bool changed = WriteGeneratedTables(args.write);
    std::cout << args.write << (changed ? ": tables regenerated\n" : ": tables up to date\n");
    return 0;
  }
  std::cout << OptionTable(args.section.empty() ? "features" : args.section);
  return 0;
}

}  // namespace

void AddOptionsDocCommand(CLI::App& app, const std::string&, CommandAction* action) {
  auto args = std::make_shared<OptionsDocArguments>();
  CLI::App* command = app.add_subcommand(
      "options-doc",
      "Print the option table of a configuration section, as configs/README.md shows it, "
      "or regenerate the tables of that file (--write)");
  command->add_option("SECTION", args->section,
                      "A configuration section (sequence, select, tracker, ...) or features");
  command->add_option("--write", args->write,
                      "Regenerate the tables between the <!-- options: SECTION --> markers of "
                      "this file (configs/README.md)");
  command->callback([args, action] { *action = [args] { return OptionsDoc(*args); }; });
}

ATTEND_COMMAND(150, "options-doc", AddOptionsDocCommand);

}  // namespace attend
