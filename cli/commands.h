// The subcommands of `attend` (SPEC 3.2). A command is one file, cli/NAME_command.cc, whose
// Add function declares its options on the CLI11 app and sets `action` to the function that
// runs it after a successful parse, and one registration line at the end of that file:
//
//   ATTEND_COMMAND(30, "segment", AddSegmentCommand);
//
// `order` places the command in `attend --help` (the registrations are added in that order,
// whatever order the linker gives the files).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace attend {

using CommandAction = std::function<int()>;
// `command_line` is the whole invocation, recorded in what a command writes.
using AddCommandFunction = void (*)(CLI::App& app, const std::string& command_line,
                                    CommandAction* action);

// A command's registration (ATTEND_COMMAND), made while the program starts.
class CommandRegistration {
 public:
  CommandRegistration(int order, const char* name, AddCommandFunction add);
};

#define ATTEND_COMMAND(order, name, add)                                               \
  static const ::attend::CommandRegistration attend_command_registration_##add(order, \
                                                                              name, add)

// Adds every registered command to `app`, in their order.
void AddCommands(CLI::App& app, const std::string& command_line, CommandAction* action);

// The function that declares the command called `name`; nullptr when there is none.
AddCommandFunction FindCommand(const std::string& name);

}  // namespace attend
