// After (or while) a job array runs: what succeeded, what failed and why, from the tasks'
// result files and the scheduler's view; and the indices worth submitting again.
#pragma once

#include <string>
#include <vector>

#include "batch/job_dir.h"
#include "batch/slurm.h"

namespace brdfrig::batch {

struct CollectedItem {
  int index = 0;
  std::filesystem::path capture, material;
  enum class Outcome {
    kSucceeded,  // material written (or up to date), every position used: exit status 0
    kPartial,    // material written without some positions: exit status 3
    kFailed,     // the task ran and failed (nothing written for it): exit status 1
    kNoResult,   // the task left no result: killed, preempted, timed out, never ran
    kActive,     // pending or running now
  } outcome = Outcome::kNoResult;
  std::string why;  // the failure's message, the scheduler's state, the dropped positions
  double seconds = 0;
};

struct CollectReport {
  std::vector<CollectedItem> items;
  std::vector<std::string> up_to_date;  // skipped when the job was prepared
  std::string scheduler;                // where the scheduler states came from
  int Count(CollectedItem::Outcome outcome) const;
  // Items without a written material: failed, without a result, pending or running.
  int NotDone() const;
  // Failed and result-less items that are not pending or running: what to submit again.
  std::vector<int> ToResubmit() const;
  // As `brdfrig reconstruct`: 0 every item complete, 3 some partial, 1 any failed, without a
  // result or still active.
  int ExitStatus() const;
  std::string Summary() const;  // one line per item not succeeded, then the counts
};

std::string OutcomeName(CollectedItem::Outcome outcome);

// Reads the manifest and results/ of `dir`; `scheduler` explains items without a result.
CollectReport Collect(const JobDir& dir, const SchedulerView& scheduler);

}  // namespace brdfrig::batch
