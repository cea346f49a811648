#include "fuzz/cli_support.h"

#include <iostream>
#include <streambuf>

#include "fuzz/fuzz_support.h"

namespace attend::fuzz {

namespace {

class NullBuffer : public std::streambuf {
 protected:
  int overflow(int c) override { return traits_type::not_eof(c); }
  std::streamsize xsputn(const char*, std::streamsize n) override { return n; }
};

}  // namespace

void SilenceStandardOutput() {
  static NullBuffer null_buffer;
  std::cout.rdbuf(&null_buffer);
}

int RunCommand(const std::vector<std::string>& args) {
  CLI::App app;
  CommandAction action;
  std::string command_line = "attend";
  for (const std::string& arg : args) command_line += " " + arg;
  const AddCommandFunction add = args.empty() ? nullptr : FindCommand(args[0]);
  if (add == nullptr) Fail("no such command: " + command_line);
  add(app, command_line, &action);
  std::vector<const char*> argv = {"attend"};
  for (const std::string& arg : args) argv.push_back(arg.c_str());
  try {
    app.parse(static_cast<int>(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    Fail("the target's command line is refused: " + command_line + ": " + e.what());
  }
  return action();
}

}  // namespace attend::fuzz
