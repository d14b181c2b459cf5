#include "batch/sbatch_script.h"

#include <sstream>

#include "batch/array_spec.h"
#include "common/atomic_file.h"
#include "common/option_check.h"
#include "common/subprocess.h"

namespace brdfrig::batch {

namespace {

bool OnlyChars(const std::string& text, const std::string& allowed) {
  return text.find_first_not_of(allowed) == std::string::npos;
}

constexpr const char* kDigits = "0123456789";
constexpr const char* kNameChars =
    "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-.,";

}  // namespace

void SbatchOptions::Validate() const {
  CheckOption(brdfrig.is_absolute(), "SbatchOptions.brdfrig", brdfrig,
              "an absolute path (the binary as installed on the cluster's nodes)");
  CheckOption(!job_name.empty() && OnlyChars(job_name, kNameChars), "SbatchOptions.job_name",
              job_name, "letters, digits, '_', '-', '.'");
  CheckOption(OnlyChars(partition, kNameChars), "SbatchOptions.partition", partition,
              "empty (the default partition) or partition names separated by ','");
  CheckOption(!time.empty() && OnlyChars(time, std::string(kDigits) + ":-") &&
                  std::isdigit(static_cast<unsigned char>(time.front())) &&
                  std::isdigit(static_cast<unsigned char>(time.back())),
              "SbatchOptions.time", time,
              "a Slurm time limit: MM, MM:SS, HH:MM:SS, D-HH, D-HH:MM or D-HH:MM:SS");
  const std::size_t digits = mem_per_task.find_first_not_of(kDigits);
  CheckOption(
      mem_per_task.empty() || (digits > 0 && (digits == std::string::npos ||
                                              (digits + 1 == mem_per_task.size() &&
                                               OnlyChars(mem_per_task.substr(digits), "KMGT")))),
      "SbatchOptions.mem_per_task", mem_per_task,
      "empty (the cluster's default) or a size such as 4000 (MB) or 4G");
  CheckOption(cpus_per_task >= 1, "SbatchOptions.cpus_per_task", cpus_per_task, ">= 1");
  CheckOption(throttle >= 0, "SbatchOptions.throttle", throttle, ">= 0 (0 = no limit)");
}

std::string SbatchScript(const SbatchOptions& options, const JobDir& dir, int items) {
  options.Validate();
  std::vector<int> all(static_cast<std::size_t>(items));
  for (int i = 0; i < items; ++i) all[i] = i;
  std::ostringstream s;
  s << "#!/bin/bash\n"
    << "# Written by `brdfrig batch prepare` (brdfrig " << BRDFRIG_VERSION << "): task i\n"
    << "# reconstructs item i of " << dir.manifest().string() << ".\n"
    << "# Submit with `brdfrig batch submit " << dir.root.string() << "` (or plain sbatch);\n"
    << "# `brdfrig batch collect` reports the outcome and resubmits only the failures.\n"
    << "#SBATCH --job-name=" << options.job_name << "\n"
    << "#SBATCH --array=" << ArraySpec(all, options.throttle) << "\n";
  if (!options.partition.empty()) s << "#SBATCH --partition=" << options.partition << "\n";
  s << "#SBATCH --time=" << options.time << "\n";
  if (!options.mem_per_task.empty()) s << "#SBATCH --mem=" << options.mem_per_task << "\n";
  s << "#SBATCH --ntasks=1\n"
    << "#SBATCH --cpus-per-task=" << options.cpus_per_task << "\n"
    << "#SBATCH --chdir=" << dir.root.string() << "\n"
    << "#SBATCH --output=" << (dir.logs() / "%A_%a.out").string() << "\n"
    << "exec " << ShellQuoted({options.brdfrig.string(), "batch", "run", dir.root.string()})
    << "\n";
  return s.str();
}

int ScriptThrottle(const std::filesystem::path& script) {
  std::istringstream lines(ReadFileToString(script));
  std::string line;
  const std::string key = "#SBATCH --array=";
  while (std::getline(lines, line)) {
    if (!line.starts_with(key)) continue;
    const std::size_t percent = line.find('%');
    return percent == std::string::npos ? 0 : std::atoi(line.c_str() + percent + 1);
  }
  return 0;
}

}  // namespace brdfrig::batch
