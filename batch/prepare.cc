#include "batch/prepare.h"

#include "common/atomic_file.h"
#include "common/error.h"
#include "common/option_check.h"

namespace brdfrig::batch {

namespace fs = std::filesystem;

void PrepareOptions::Validate() const {
  batch.Validate();
  sbatch.Validate();
  // #SBATCH lines are not shell words (no quoting) and '%' starts an --output pattern.
  // Checked as the absolute path the script names: a relative one inherits the current
  // directory's name.
  const std::string absolute = job_dir.empty() ? "" : fs::absolute(job_dir).string();
  CheckOption(!absolute.empty() && absolute.find_first_of(" \t\n%") == std::string::npos,
              "PrepareOptions.job_dir", absolute, "a path without spaces or '%'");
}

Manifest PrepareJob(const PrepareOptions& options, const reconstruct::ProgressCallback& progress) {
  options.Validate();
  const JobDir dir(options.job_dir);
  if (fs::exists(dir.manifest())) {
    throw FileError(dir.manifest().string(),
                    "a job was already prepared here: collect it (`brdfrig batch collect`), or "
                    "choose a new job directory");
  }
  const Manifest manifest = MakeManifest(options.batch, progress);
  CreateDirectories(dir.results());
  CreateDirectories(dir.logs());
  if (!manifest.items.empty()) {
    WriteFileAtomically(dir.script(),
                        SbatchScript(options.sbatch, dir, static_cast<int>(manifest.items.size())));
    fs::permissions(dir.script(), fs::perms::owner_exec | fs::perms::group_exec,
                    fs::perm_options::add);
  }
  // The manifest last: its presence says the directory is complete.
  WriteManifest(dir.manifest(), manifest);
  return manifest;
}

}  // namespace brdfrig::batch
