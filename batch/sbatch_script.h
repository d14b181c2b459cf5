// The job-array script for a prepared job directory. It names the installed brdfrig and the
// job directory by absolute path and nothing else: the cluster's nodes need that binary (at
// that path) and read access to the archive, write access to the fits and the job directory;
// they need neither our build directory nor our working directory.
#pragma once

#include <filesystem>
#include <string>

#include "batch/job_dir.h"

namespace brdfrig::batch {

struct SbatchOptions {
  std::filesystem::path brdfrig;  // absolute path of brdfrig on the cluster's nodes
  std::string job_name = "brdfrig-reconstruct";
  std::string partition;         // empty: the cluster's default partition
  std::string time = "1:00:00";  // per task, Slurm's format: MM, HH:MM:SS, D-HH:MM:SS, ...
  std::string mem_per_task;      // e.g. "4G"; empty: the cluster's default
  int cpus_per_task = 1;
  int throttle = 0;  // at most this many tasks at once (the array's %N); 0 = no limit
  void Validate() const;
};

// The script for `items` array tasks (indices 0..items-1), each running
// `brdfrig batch run <job dir>` (the index comes from SLURM_ARRAY_TASK_ID).
std::string SbatchScript(const SbatchOptions& options, const JobDir& dir, int items);

// The throttle of a written script (its "#SBATCH --array=...%N" line; 0 when it has none), so
// that resubmissions keep what the lab set, also after editing the script by hand.
int ScriptThrottle(const std::filesystem::path& script);

}  // namespace brdfrig::batch
