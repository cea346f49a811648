// The subcommands of `attend` (SPEC 3.2). Each Add* function declares its options on the
// CLI11 app and sets `action` to the function that runs it after a successful parse.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>

namespace attend {

using CommandAction = std::function<int()>;

// `command_line` is the whole invocation, recorded in what a command writes.
void AddRunCommand(CLI::App& app, const std::string& command_line, CommandAction* action);
void AddSynthCommand(CLI::App& app, const std::string& command_line, CommandAction* action);
void AddSegmentCommand(CLI::App& app, const std::string& command_line, CommandAction* action);
void AddDisparityCommand(CLI::App& app, const std::string& command_line, CommandAction* action);
void AddTrackCommand(CLI::App& app, const std::string& command_line, CommandAction* action);
void AddEvalTrackingCommand(CLI::App& app, const std::string& command_line,
                            CommandAction* action);
void AddEvalCommand(CLI::App& app, const std::string& command_line, CommandAction* action);
void AddSkinTrainCommand(CLI::App& app, const std::string& command_line, CommandAction* action);
void AddCompareCommand(CLI::App& app, const std::string& command_line, CommandAction* action);
void AddReportCommand(CLI::App& app, const std::string& command_line, CommandAction* action);
void AddSaliencyCommand(CLI::App& app, const std::string& command_line,
                        CommandAction* action);
void AddEvalFixationsCommand(CLI::App& app, const std::string& command_line,
                             CommandAction* action);
void AddFitWeightsCommand(CLI::App& app, const std::string& command_line, CommandAction* action);

}  // namespace attend
