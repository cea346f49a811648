#include "util/subprocess.h"

#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

extern char** environ;

namespace attend {

namespace {

std::string ReadWhole(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// A file name for captured output, made and closed here; removed by the caller.
std::string TemporaryFile() {
  const char* folder = std::getenv("TMPDIR");
  std::string pattern = std::string(folder != nullptr && *folder != '\0' ? folder : "/tmp") +
                        "/attend-capture-XXXXXX";
  const int fd = mkstemp(pattern.data());
  if (fd < 0) return "";
  close(fd);
  return pattern;
}

}  // namespace

pid_t StartProcess(const std::vector<std::string>& argv, const std::string& stdout_path,
                   const std::string& stderr_path, std::string* error, bool own_group) {
  error->clear();
  if (argv.empty()) {
    *error = "no program given";
    return -1;
  }
  std::vector<std::string> words = argv;
  std::vector<char*> pointers;
  for (std::string& word : words) pointers.push_back(word.data());
  pointers.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!stdout_path.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, stdout_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  if (!stderr_path.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, stderr_path.c_str(),
                                     O_WRONLY | O_CREAT | O_TRUNC, 0644);
  }
  // The child starts with the default handlers and no blocked signals, whatever the parent set.
  posix_spawnattr_t attributes;
  posix_spawnattr_init(&attributes);
  sigset_t none, all;
  sigemptyset(&none);
  sigfillset(&all);
  posix_spawnattr_setsigmask(&attributes, &none);
  posix_spawnattr_setsigdefault(&attributes, &all);
  short flags = POSIX_SPAWN_SETSIGMASK | POSIX_SPAWN_SETSIGDEF;
  if (own_group) {
    flags |= POSIX_SPAWN_SETPGROUP;
    posix_spawnattr_setpgroup(&attributes, 0);
  }
  posix_spawnattr_setflags(&attributes, flags);
  pid_t pid = -1;
  const int result = argv[0].find('/') == std::string::npos
                         ? posix_spawnp(&pid, pointers[0], &actions, &attributes,
                                        pointers.data(), environ)
                         : posix_spawn(&pid, pointers[0], &actions, &attributes, pointers.data(),
                                       environ);
  posix_spawnattr_destroy(&attributes);
  posix_spawn_file_actions_destroy(&actions);
  if (result != 0) {
    *error = argv[0] + ": " + std::strerror(result);
    return -1;
  }
  return pid;
}

ProcessExit WaitProcess(pid_t pid) {
  int status = 0;
  struct rusage usage {};
  while (wait4(pid, &status, 0, &usage) < 0) {
    if (errno != EINTR) return {127, 0};
  }
  ProcessExit exit;
  exit.peak_rss_kb = usage.ru_maxrss;
  if (WIFSIGNALED(status)) {
    exit.signal = WTERMSIG(status);
  } else {
    exit.code = WEXITSTATUS(status);
  }
  return exit;
}

bool ProcessAlive(pid_t pid) { return pid > 0 && (kill(pid, 0) == 0 || errno == EPERM); }

CapturedRun RunCaptured(const std::vector<std::string>& argv) {
  CapturedRun run;
  const std::string out = TemporaryFile();
  const std::string err = TemporaryFile();
  if (out.empty() || err.empty()) {
    run.start_error = "cannot create a temporary file for its output";
  } else {
    const pid_t pid = StartProcess(argv, out, err, &run.start_error);
    if (pid > 0) {
      run.started = true;
      run.exit = WaitProcess(pid);
      run.out = ReadWhole(out);
      run.err = ReadWhole(err);
    }
  }
  std::error_code ignored;
  if (!out.empty()) std::filesystem::remove(out, ignored);
  if (!err.empty()) std::filesystem::remove(err, ignored);
  // posix_spawnp reports a program missing from PATH through the child's exit status 127.
  if (run.started && run.exit.code == 127 && run.out.empty() && run.err.empty()) {
    run.started = false;
    run.start_error = argv[0] + ": not found";
  }
  return run;
}

std::string ShellQuote(const std::vector<std::string>& argv) {
  std::string line;
  for (const std::string& word : argv) {
    if (!line.empty()) line += ' ';
    const bool plain =
        !word.empty() && word.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                                "0123456789_-./=:,+%@") == std::string::npos;
    if (plain) {
      line += word;
      continue;
    }
    line += '\'';
    for (const char c : word) {
      if (c == '\'') {
        line += "'\\''";
      } else {
        line += c;
      }
    }
    line += '\'';
  }
  return line;
}

std::string HostName() {
  char name[256] = {0};
  gethostname(name, sizeof(name) - 1);
  return name;
}

std::string SelfExecutable() {
  std::error_code error;
  const std::filesystem::path path = std::filesystem::read_symlink("/proc/self/exe", error);
  return error ? std::string() : path.string();
}

}  // namespace attend
