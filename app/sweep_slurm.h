// The Slurm executor of `attend sweep` (docs/SWEEPS.md): a job array with one task a cell,
// each task `attend sweep DIR --cell $SLURM_ARRAY_TASK_ID`, submitted with sbatch; and what
// the scheduler says about the tasks, for --status.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "app/sweep_folder.h"

namespace attend {

// Slurm's --array value for the cell indexes ("0-3,5,7-9"), with "%M" when `throttle` > 0.
std::string SlurmArraySpec(std::vector<int> indexes, int throttle);

// The batch script of a job array over `indexes` of `sweep`, running `program`.
// ConfigError for a sweep folder path Slurm's #SBATCH lines cannot hold (white space).
std::string SlurmBatchScript(const StoredSweep& sweep, const std::vector<int>& indexes,
                             const SlurmSettings& slurm, const std::string& program,
                             const std::string& command_line);

struct SlurmSubmission {
  std::string job_id;
  std::string script_path;
};

// Writes the script to DIR/slurm/array-N.sbatch, submits it with `sbatch --parsable` and
// records the job in DIR/slurm/jobs.json. InputError (exit 3) with sbatch's own message when
// sbatch is missing or refuses the job.
SlurmSubmission SubmitSlurmArray(const StoredSweep& sweep, const std::string& script);

// What Slurm says about the sweep's array tasks, by cell index: PENDING, RUNNING, ... for
// those still queued; for finished ones, their final state (COMPLETED, FAILED, TIMEOUT,
// CANCELLED, OUT_OF_MEMORY) where sacct or scontrol still know it.
struct SlurmView {
  bool has_jobs = false;  // the sweep was submitted to Slurm at least once
  bool queried = false;   // squeue answered
  std::string note;       // why Slurm could not be asked
  std::map<int, std::string> queued;  // cell index to state, for tasks squeue lists
  std::map<int, std::string> task;    // cell index to its latest JOB_TASK id
};
SlurmView QuerySlurm(const StoredSweep& sweep);

// The final state of a finished array task (JOB_TASK) from sacct, else scontrol; "" unknown.
std::string SlurmFinalState(const std::string& job_task);

}  // namespace attend
