#include "cli/commands.h"

#include <algorithm>
#include <tuple>
#include <vector>

#include "util/error.h"

namespace attend {

namespace {

struct Registered {
  int order;
  std::string name;
  AddCommandFunction add;
};

// Built while the program starts (the registrations' static constructors), read after.
std::vector<Registered>& Registry() {
  static std::vector<Registered> registry;
  return registry;
}

}  // namespace

CommandRegistration::CommandRegistration(int order, const char* name, AddCommandFunction add) {
  for (const Registered& command : Registry()) {
    ATTEND_CHECK(command.name != name && command.order != order)
        << "command " << name << " (order " << order << ") registered twice, or beside "
        << command.name << " at the same order";
  }
  Registry().push_back({order, name, add});
}

void AddCommands(CLI::App& app, const std::string& command_line, CommandAction* action) {
  std::vector<Registered> commands = Registry();
  std::sort(commands.begin(), commands.end(),
            [](const Registered& a, const Registered& b) { return a.order < b.order; });
  for (const Registered& command : commands) command.add(app, command_line, action);
}

AddCommandFunction FindCommand(const std::string& name) {
  for (const Registered& command : Registry()) {
    if (command.name == name) return command.add;
  }
  return nullptr;
}

}  // namespace attend
