// The command registry (cli/commands.h): every command file's registration is linked in, the
// commands are added in their order, and each is found by its name.
#include "cli/commands.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace attend {
namespace {

// The commands of SPEC 3.2, in the order `attend --help` lists them.
const std::vector<std::string> kCommands = {
    "run",   "synth",      "calibrate", "segment", "disparity", "track", "eval-tracking",  "track-detections",
    "eval",  "skin-train", "compare", "report",    "saliency", "eval-fixations", "eval-scanpaths", "fit-weights",
    "sweep", "options-doc"};

TEST(Commands, EveryCommandIsAddedInItsOrder) {
  CLI::App app;
  CommandAction action;
  AddCommands(app, "attend", &action);
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands({})) names.push_back(command->get_name());
  EXPECT_EQ(names, kCommands);
}

TEST(Commands, EachIsFoundByItsNameAndNoOther) {
  for (const std::string& name : kCommands) {
    const AddCommandFunction add = FindCommand(name);
    ASSERT_NE(add, nullptr) << name;
    CLI::App app;
    CommandAction action;
    add(app, "attend " + name, &action);
    ASSERT_EQ(app.get_subcommands({}).size(), 1u) << name;
    EXPECT_EQ(app.get_subcommands({}).front()->get_name(), name);
  }
  EXPECT_EQ(FindCommand("runn"), nullptr);
  EXPECT_EQ(FindCommand(""), nullptr);
}

}  // namespace
}  // namespace attend
