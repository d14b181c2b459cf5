// A batch job directory: everything one sharded reconstruction of an archive needs and leaves,
// in one place a cluster's nodes can all read (the archive and the fits may live elsewhere).
//
//   manifest.json       the captures to process, by index (batch/manifest.h)
//   array.sbatch        the job-array script (batch/sbatch_script.h)
//   submissions.txt     one line per sbatch call: "<job id> <array spec>"
//   results/<i>.json    the outcome of item i, written atomically by its task (batch/task.h)
//   logs/<job>_<i>.out  the task's stdout and stderr (Slurm writes them)
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace brdfrig::batch {

struct JobDir {
  std::filesystem::path root;  // absolute
  explicit JobDir(const std::filesystem::path& dir);
  std::filesystem::path manifest() const { return root / "manifest.json"; }
  std::filesystem::path script() const { return root / "array.sbatch"; }
  std::filesystem::path submissions() const { return root / "submissions.txt"; }
  std::filesystem::path results() const { return root / "results"; }
  std::filesystem::path result(int index) const;
  std::filesystem::path logs() const { return root / "logs"; }
};

struct Submission {
  std::string job_id;
  std::string array;  // the --array spec it was submitted with, e.g. "0-9%4" or "3,7"
};

// Every submission recorded in the job directory, oldest first (none: empty).
std::vector<Submission> ReadSubmissions(const JobDir& dir);
// Appends one line to submissions.txt (the whole file rewritten atomically).
void RecordSubmission(const JobDir& dir, const Submission& submission);

}  // namespace brdfrig::batch
