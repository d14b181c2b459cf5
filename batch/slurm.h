// Talking to Slurm through its commands (sbatch, squeue, sacct), as a user would: no library,
// so the cluster's own client configuration (SLURM_CONF, munge) applies unchanged.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "batch/job_dir.h"

namespace brdfrig::batch {

// `sbatch --parsable --array=<spec> <dir's script>`; records the submission in
// submissions.txt. Throws Error with sbatch's own message when it refuses. SIGINT, SIGTERM and
// SIGHUP arriving meanwhile take effect once the submission is recorded (or refused).
Submission SubmitArray(const JobDir& dir, const std::vector<int>& indices, int throttle);

// What the scheduler says about one array task.
struct TaskState {
  std::string job_id;  // the array job it belongs to
  std::string state;  // PENDING, RUNNING, COMPLETED, FAILED, CANCELLED, TIMEOUT, OUT_OF_MEMORY, ...
  std::string reason;  // squeue's reason or sacct's exit code ("0:15" = killed by signal 15)
  bool Active() const {
    return state == "PENDING" || state == "RUNNING" || state == "CONFIGURING" ||
           state == "COMPLETING" || state == "REQUEUED" || state == "RESIZING" ||
           state == "SUSPENDED";
  }
};

struct SchedulerView {
  // Task index → its state in the latest submission that knows it.
  std::map<int, TaskState> tasks;
  // Which command answered ("sacct", "squeue"), or why neither did.
  std::string source;
  int Active() const;
};

// Asks sacct about every recorded submission (it remembers finished tasks and why they ended)
// and, where accounting is disabled, squeue (which forgets a task MinJobAge after it ended).
SchedulerView QueryScheduler(const std::vector<Submission>& submissions);

// Parses `squeue -h -t all -o "%i|%T|%r"` or `sacct -n -P -X -o JobID,State,ExitCode` output
// for the job ids given (later ids win); exposed for tests.
void ParseSchedulerLines(const std::string& text, const std::vector<std::string>& job_ids,
                         std::map<int, TaskState>& tasks);

}  // namespace brdfrig::batch
