// `brdfrig batch prepare`: a job directory for an archive — the manifest of what needs a
// reconstruction and the job-array script — ready to submit.
#pragma once

#include "batch/job_dir.h"
#include "batch/manifest.h"
#include "batch/sbatch_script.h"

namespace brdfrig::batch {

struct PrepareOptions {
  reconstruct::BatchOptions batch;  // inputs, output and the reconstruction settings
  SbatchOptions sbatch;
  std::filesystem::path job_dir;  // created; must not hold another job's manifest
  void Validate() const;
};

// Writes manifest.json and array.sbatch into options.job_dir and creates results/ and logs/.
// A job directory is prepared once: preparing over an existing manifest is an error (its
// results would be mistaken for the new items'). Throws Error / FileError naming the path.
Manifest PrepareJob(const PrepareOptions& options,
                    const reconstruct::ProgressCallback& progress = {});

}  // namespace brdfrig::batch
