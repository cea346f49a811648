// Running one `attend` subcommand in the fuzz process, as the program runs it: the command's
// own CLI11 declaration and action from cli/, with its standard output sent nowhere.
#pragma once

#include <CLI/CLI.hpp>
#include <string>
#include <vector>

#include "cli/commands.h"

namespace attend::fuzz {

// Sends std::cout nowhere for the rest of the process (the commands print their reports there).
void SilenceStandardOutput();

// Declares the command `args[0]` (a registered command, cli/commands.h) on a fresh CLI11 app,
// parses `args` (without the program name) and runs the command's action. A command line the
// app refuses stops the process: the targets build their command lines themselves, so that is
// a mistake of the target.
int RunCommand(const std::vector<std::string>& args);

}  // namespace attend::fuzz
