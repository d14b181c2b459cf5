// One task of the job array: reconstructs item i of the manifest and records what happened in
// results/<i>.json. The old result is removed first and the new one written atomically at the
// end, so a task killed or preempted at any instant leaves no result (collect reports it as
// "no result" with the scheduler's word on why), never a torn or a stale one; the material
// itself is written atomically by the reconstruction.
#pragma once

#include <string>
#include <vector>

#include "batch/job_dir.h"
#include "reconstruct/batch.h"

namespace brdfrig::batch {

// The item index a Slurm array task is to process: SLURM_ARRAY_TASK_ID. Throws Error when it
// is not set (not inside an array job) or not a non-negative number.
int TaskIndexFromEnvironment();

struct TaskResult {
  int index = -1;
  reconstruct::BatchItem item;  // input, material_file, status, message, dropped, seconds
  int exit_status = 1;          // of `brdfrig reconstruct` for this item: 0, 3 or 1
  std::string job;              // "<array job id>_<task id>" under Slurm, else ""
  std::string host;
};

// Runs item `index` of dir's manifest. Errors of the item itself (a capture that cannot be
// read, a fit that fails) are recorded in the result; a missing or unreadable manifest, an
// index out of range or a manifest from another brdfrig version throws Error.
TaskResult RunTask(const JobDir& dir, int index,
                   const reconstruct::ProgressCallback& progress = {});

std::string SerializeTaskResult(const TaskResult& result);
// Throws FileError naming the file when it is malformed.
TaskResult ReadTaskResult(const std::filesystem::path& file);

}  // namespace brdfrig::batch
