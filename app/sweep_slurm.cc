#include "app/sweep_slurm.h"

#include <algorithm>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "app/sweep_records.h"
#include "util/error.h"
#include "util/json_text.h"
#include "util/output_folder.h"
#include "util/strings.h"
#include "util/subprocess.h"
#include "util/timer.h"

namespace attend {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

fs::path JobsPath(const StoredSweep& sweep) { return fs::path(sweep.dir) / "slurm" / "jobs.json"; }

Json ReadJobs(const StoredSweep& sweep) {
  std::ifstream in(JobsPath(sweep));
  if (!in) return Json::array();
  try {
    return Json::parse(in);
  } catch (const std::exception& e) {
    throw InputError(JobsPath(sweep).string() + ": not valid JSON (" + e.what() + ")");
  }
}

std::string Trim(const std::string& text) {
  const std::size_t first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return "";
  return text.substr(first, text.find_last_not_of(" \t\r\n") - first + 1);
}

// "JOB_TASK STATE" lines of squeue for the user's array tasks.
std::map<std::string, std::string> QueueStates(std::string* note, bool* queried) {
  std::map<std::string, std::string> states;
  std::vector<std::string> argv = {"squeue", "-h", "-r", "-o", "%F_%K %T"};
  const CapturedRun run = RunCaptured(argv);
  if (!run.started) {
    *note = "squeue is not available (" + run.start_error + "): Slurm's view is left out";
    return states;
  }
  if (run.exit.Status() != 0) {
    *note = "squeue failed: " + Trim(run.err);
    return states;
  }
  *queried = true;
  std::istringstream lines(run.out);
  std::string line;
  while (std::getline(lines, line)) {
    const std::vector<std::string> words = Split(Trim(line), ' ');
    if (words.size() >= 2) states[words[0]] = words.back();
  }
  return states;
}

}  // namespace

std::string SlurmArraySpec(std::vector<int> indexes, int throttle) {
  std::sort(indexes.begin(), indexes.end());
  indexes.erase(std::unique(indexes.begin(), indexes.end()), indexes.end());
  std::string spec;
  for (std::size_t i = 0; i < indexes.size();) {
    std::size_t j = i;
    while (j + 1 < indexes.size() && indexes[j + 1] == indexes[j] + 1) ++j;
    if (!spec.empty()) spec += ",";
    spec += std::to_string(indexes[i]);
    if (j > i) spec += "-" + std::to_string(indexes[j]);
    i = j + 1;
  }
  if (throttle > 0) spec += "%" + std::to_string(throttle);
  return spec;
}

std::string SlurmBatchScript(const StoredSweep& sweep, const std::vector<int>& indexes,
                             const SlurmSettings& slurm, const std::string& program,
                             const std::string& command_line) {
  for (const std::string& path : {sweep.dir, program}) {
    if (path.find_first_of(" \t\n\"'\\") != std::string::npos) {
      throw ConfigError(path + ": Slurm's #SBATCH lines cannot hold a path with white space or "
                        "quotes; move the sweep folder or the program");
    }
  }
  std::string script = "#!/bin/bash\n";
  script += "# attend sweep: " + std::to_string(indexes.size()) + " cells of " + sweep.dir +
            ", one array task a cell (docs/SWEEPS.md).\n";
  script += "# Written by: " + command_line + "\n";
  script += "#SBATCH --job-name=attend-sweep\n";
  script += "#SBATCH --array=" + SlurmArraySpec(indexes, slurm.throttle) + "\n";
  script += "#SBATCH --output=" + sweep.dir + "/slurm/%A_%a.out\n";
  script += "#SBATCH --cpus-per-task=" + std::to_string(slurm.cpus_per_task) + "\n";
  if (!slurm.partition.empty()) script += "#SBATCH --partition=" + slurm.partition + "\n";
  if (!slurm.time.empty()) script += "#SBATCH --time=" + slurm.time + "\n";
  if (!slurm.mem.empty()) script += "#SBATCH --mem=" + slurm.mem + "\n";
  script += "exec " + program + " sweep " + sweep.dir + " --cell \"$SLURM_ARRAY_TASK_ID\"\n";
  return script;
}

SlurmSubmission SubmitSlurmArray(const StoredSweep& sweep, const std::string& script) {
  const fs::path folder = fs::path(sweep.dir) / "slurm";
  std::error_code error;
  fs::create_directories(folder, error);
  if (error) throw OutputError(folder.string() + ": cannot create the folder: " + error.message());
  Json jobs = ReadJobs(sweep);
  SlurmSubmission submission;
  submission.script_path = (folder / ("array-" + std::to_string(jobs.size()) + ".sbatch")).string();
  ReplaceFileText(submission.script_path, script, "the batch script");
  const CapturedRun run = RunCaptured({"sbatch", "--parsable", submission.script_path});
  if (!run.started) {
    throw InputError("sbatch: " + run.start_error +
                     " (Slurm's client, Debian package slurm-client; --local runs the cells on "
                     "this machine)");
  }
  if (run.exit.Status() != 0) {
    throw InputError("sbatch refused " + submission.script_path + " (exit status " +
                     std::to_string(run.exit.Status()) + "): " + Trim(run.err + run.out));
  }
  // --parsable prints "JOB" or "JOB;CLUSTER".
  submission.job_id = Split(Trim(run.out), ';')[0];
  if (submission.job_id.empty() ||
      submission.job_id.find_first_not_of("0123456789") != std::string::npos) {
    throw InputError("sbatch answered '" + Trim(run.out) + "', not a job id");
  }
  std::vector<int> cells;
  const std::string marker = "#SBATCH --array=";
  const std::size_t at = script.find(marker);
  jobs.push_back({{"job", submission.job_id},
                  {"array", at == std::string::npos
                                ? ""
                                : script.substr(at + marker.size(),
                                                script.find('\n', at) - at - marker.size())},
                  {"script", submission.script_path},
                  {"submitted", UtcTimestamp()}});
  ReplaceFileText(JobsPath(sweep).string(), JsonText(jobs, 2) + "\n", "the job list");
  return submission;
}

namespace {

// The cell indexes an --array value covers ("0-3,5%2").
std::vector<int> ArrayIndexes(const std::string& spec) {
  std::vector<int> indexes;
  const std::string list = spec.substr(0, spec.find('%'));
  for (const std::string& part : Split(list, ',')) {
    const std::size_t dash = part.find('-');
    try {
      const int first = std::stoi(part.substr(0, dash));
      const int last = dash == std::string::npos ? first : std::stoi(part.substr(dash + 1));
      for (int i = first; i <= last; ++i) indexes.push_back(i);
    } catch (const std::exception&) {
      continue;
    }
  }
  return indexes;
}

}  // namespace

SlurmView QuerySlurm(const StoredSweep& sweep) {
  SlurmView view;
  const Json jobs = ReadJobs(sweep);
  if (jobs.empty()) return view;
  view.has_jobs = true;
  for (const Json& job : jobs) {
    for (const int index : ArrayIndexes(job.value("array", ""))) {
      view.task[index] = job.value("job", "") + "_" + std::to_string(index);
    }
  }
  const std::map<std::string, std::string> states = QueueStates(&view.note, &view.queried);
  for (const auto& [index, task] : view.task) {
    const auto found = states.find(task);
    if (found != states.end()) view.queued[index] = found->second;
  }
  return view;
}

std::string SlurmFinalState(const std::string& job_task) {
  const CapturedRun sacct = RunCaptured({"sacct", "-n", "-X", "-P", "-o", "State", "-j", job_task});
  if (sacct.started && sacct.exit.Status() == 0) {
    const std::string state = Trim(Split(Trim(sacct.out), '\n').empty()
                                       ? std::string()
                                       : Split(Trim(sacct.out), '\n')[0]);
    if (!state.empty()) return Split(state, ' ')[0];
  }
  const CapturedRun scontrol = RunCaptured({"scontrol", "-o", "show", "job", job_task});
  if (scontrol.started && scontrol.exit.Status() == 0) {
    const std::size_t at = scontrol.out.find("JobState=");
    if (at != std::string::npos) {
      const std::size_t end = scontrol.out.find_first_of(" \n", at);
      return scontrol.out.substr(at + 9, end == std::string::npos ? std::string::npos : end - at - 9);
    }
  }
  return "";
}

}  // namespace attend
