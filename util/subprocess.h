// Starting other programs and waiting for them: the cells of `attend sweep` (each a process of
// attend itself) and the Slurm client commands (sbatch, squeue, scontrol).
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace attend {

// How a child process ended.
struct ProcessExit {
  int code = 0;    // its exit status when it exited
  int signal = 0;  // the signal that ended it, 0 when it exited
  long peak_rss_kb = 0;  // its peak resident set, KiB (getrusage's ru_maxrss), from WaitProcess
  // The shell's convention: the exit status, or 128 + the signal.
  int Status() const { return signal != 0 ? 128 + signal : code; }
};

// Starts argv[0] (a path, or a name looked up on PATH) with `argv`, its standard output and
// error written to the files named (created or truncated; "" keeps the parent's). With
// `own_group` it leads a process group of its own, so that a terminal's Ctrl-C reaches only the
// parent, which passes it on. Returns the child's pid; "" in `error` on success, else why it
// could not start (and -1).
pid_t StartProcess(const std::vector<std::string>& argv, const std::string& stdout_path,
                   const std::string& stderr_path, std::string* error, bool own_group = false);

// Waits for `pid` to end (through interrupted waits), with its peak resident set.
ProcessExit WaitProcess(pid_t pid);

// Whether a process of this pid exists (on this machine).
bool ProcessAlive(pid_t pid);

// A command run to its end with its output captured.
struct CapturedRun {
  bool started = false;
  std::string start_error;  // why it did not start
  ProcessExit exit;
  std::string out;
  std::string err;
};

// Runs `argv` (argv[0] looked up on PATH) and returns its output; never throws.
CapturedRun RunCaptured(const std::vector<std::string>& argv);

// `argv` as one line a POSIX shell reads back to the same words.
std::string ShellQuote(const std::vector<std::string>& argv);

// This machine's host name.
std::string HostName();

// The path of the running program (/proc/self/exe).
std::string SelfExecutable();

}  // namespace attend
