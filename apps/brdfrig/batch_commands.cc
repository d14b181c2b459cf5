#include "apps/brdfrig/batch_commands.h"

#include <cstdio>
#include <filesystem>
#include <memory>

#include "apps/brdfrig/reconstruct_commands.h"
#include "batch/array_spec.h"
#include "batch/collect.h"
#include "batch/follow.h"
#include "batch/prepare.h"
#include "batch/sbatch_script.h"
#include "batch/slurm.h"
#include "batch/task.h"
#include "common/display_text.h"
#include "common/error.h"

namespace brdfrig::apps {
namespace {

namespace fs = std::filesystem;

void Say(const std::string& line) {
  std::fprintf(stderr, "%s\n", line.c_str());
  std::fflush(stderr);
}

void PrintSubmission(const batch::Submission& s) {
  std::printf("submitted job %s (array %s)\n", s.job_id.c_str(), s.array.c_str());
}

// The reconstruct exit statuses (0 complete, 3 partial, 1 failed) for the shell.
void ExitWith(int status, const std::string& failure) {
  if (status == 3) throw CLI::RuntimeError(3);
  if (status != 0) throw Error(failure);
}

struct PrepareArgs {
  std::vector<std::string> inputs;
  std::string output, job_dir, brdfrig;
  ReconstructFlags flags;
  batch::SbatchOptions sbatch;
  bool submit = false;
};

void RegisterPrepare(CLI::App* batch) {
  auto args = std::make_shared<PrepareArgs>();
  CLI::App* cmd = batch->add_subcommand(
      "prepare",
      "Write a job directory (manifest of the captures needing a reconstruction, sbatch "
      "job-array script) for an archive");
  cmd->add_option("captures", args->inputs, "Captures, or directories holding captures")
      ->required();
  cmd->add_option("-o,--output", args->output, "Directory of fits (one subdirectory per capture)")
      ->required();
  cmd->add_option("--job-dir", args->job_dir,
                  "The job directory to create (manifest.json, array.sbatch, results/, logs/); "
                  "on storage every node can read and write")
      ->required();
  cmd->add_option("--brdfrig", args->brdfrig,
                  "brdfrig as installed on the cluster's nodes (default: this executable)");
  cmd->add_option("--partition", args->sbatch.partition,
                  "Slurm partition (default: the cluster's)");
  cmd->add_option("--time", args->sbatch.time,
                  "Time limit per task (Slurm format, default 1:00:00)");
  cmd->add_option("--mem-per-task", args->sbatch.mem_per_task,
                  "Memory per task, e.g. 4G (default: the cluster's)");
  cmd->add_option("--cpus-per-task", args->sbatch.cpus_per_task, "CPUs per task (default 1)");
  cmd->add_option("--throttle", args->sbatch.throttle,
                  "At most this many tasks at once (0 = no limit, the default)");
  cmd->add_option("--job-name", args->sbatch.job_name, "Slurm job name");
  cmd->add_flag("--submit", args->submit, "Submit the array at once (sbatch)");
  AddReconstructFlags(cmd, args->flags);
  cmd->callback([args] {
    batch::PrepareOptions options;
    for (const std::string& input : args->inputs) options.batch.inputs.emplace_back(input);
    options.batch.output = args->output;
    ApplyReconstructFlags(args->flags, options.batch);
    options.sbatch = args->sbatch;
    options.sbatch.brdfrig =
        args->brdfrig.empty() ? fs::canonical("/proc/self/exe") : fs::path(args->brdfrig);
    options.job_dir = args->job_dir;
    const batch::Manifest manifest = batch::PrepareJob(options, Say);
    const batch::JobDir dir(options.job_dir);
    std::printf("%zu capture(s) to reconstruct, %zu up to date; manifest %s\n",
                manifest.items.size(), manifest.up_to_date.size(), dir.manifest().c_str());
    if (manifest.items.empty()) return;
    std::printf("script %s\n", dir.script().c_str());
    if (!args->submit) return;
    std::vector<int> all;
    for (const batch::ManifestItem& item : manifest.items) all.push_back(item.index);
    PrintSubmission(batch::SubmitArray(dir, all, args->sbatch.throttle));
  });
}

void RegisterSubmit(CLI::App* batch) {
  auto job_dir = std::make_shared<std::string>();
  CLI::App* cmd = batch->add_subcommand("submit", "Submit a prepared job directory's whole array");
  cmd->add_option("job_dir", *job_dir, "The job directory (batch prepare --job-dir)")->required();
  cmd->callback([job_dir] {
    const batch::JobDir dir(*job_dir);
    const auto earlier = batch::ReadSubmissions(dir);
    if (!earlier.empty()) {
      throw Error(dir.root.string() + " was submitted already (job " + earlier.back().job_id +
                  "): `brdfrig batch collect --resubmit` submits what failed");
    }
    const batch::CollectReport report = batch::Collect(dir, {});
    std::vector<int> all;
    for (const batch::CollectedItem& item : report.items) all.push_back(item.index);
    if (all.empty()) {
      std::printf("nothing to submit: every capture was up to date\n");
      return;
    }
    PrintSubmission(batch::SubmitArray(dir, all, batch::ScriptThrottle(dir.script())));
  });
}

void RegisterRun(CLI::App* batch) {
  struct Args {
    std::string job_dir;
    int index = -1;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = batch->add_subcommand(
      "run", "Reconstruct one item of a job directory (the array task's command)");
  cmd->add_option("job_dir", args->job_dir, "The job directory")->required();
  const CLI::Option* index_option =
      cmd->add_option("--index", args->index, "Item index (default: $SLURM_ARRAY_TASK_ID)");
  cmd->callback([args, index_option] {
    if (index_option->count() > 0 && args->index < 0) {
      throw OptionsError("--index " + std::to_string(args->index) +
                         ": an item index is >= 0 (items are numbered 0, 1, 2, ...)");
    }
    const batch::JobDir dir(args->job_dir);
    const int index = index_option->count() > 0 ? args->index : batch::TaskIndexFromEnvironment();
    const batch::TaskResult result = batch::RunTask(dir, index, Say);
    std::printf("%-10s %d %s -> %s (%.1f s)%s%s\n", result.item.StatusName().c_str(), index,
                DisplayPath(result.item.input.string()).c_str(),
                DisplayPath(result.item.material_file.string()).c_str(), result.item.seconds,
                result.exit_status == 1 ? ": " : "",
                result.exit_status == 1 ? OneLine(result.item.message).c_str() : "");
    for (const std::string& d : result.item.dropped)
      std::printf("           dropped %s\n", OneLine(d).c_str());
    ExitWith(result.exit_status, "item " + std::to_string(index) + " failed");
  });
}

void RegisterStatus(CLI::App* batch) {
  struct Args {
    std::string job_dir;
    bool wait = false;
    double interval_s = 10;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd =
      batch->add_subcommand("status", "Progress of a job directory's arrays (squeue/sacct)");
  cmd->add_option("job_dir", args->job_dir, "The job directory")->required();
  cmd->add_flag("--wait", args->wait, "Follow until no task is pending or running");
  cmd->add_option("--interval", args->interval_s, "Seconds between looks with --wait")
      ->check(CLI::Range(0.1, 3600.0));
  cmd->callback([args] {
    batch::FollowJob(batch::JobDir(args->job_dir), args->wait, args->interval_s,
                     [](const std::string& line) {
                       std::printf("%s\n", line.c_str());
                       std::fflush(stdout);
                     });
  });
}

void RegisterCollect(CLI::App* batch) {
  struct Args {
    std::string job_dir;
    bool resubmit = false;
  };
  auto args = std::make_shared<Args>();
  CLI::App* cmd = batch->add_subcommand(
      "collect",
      "What succeeded, what failed and why; exit status as `brdfrig reconstruct` (0, 3, 1)");
  cmd->add_option("job_dir", args->job_dir, "The job directory")->required();
  cmd->add_flag("--resubmit", args->resubmit,
                "Submit the failed and result-less items again (not those pending or running)");
  cmd->callback([args] {
    const batch::JobDir dir(args->job_dir);
    const batch::CollectReport report =
        batch::Collect(dir, batch::QueryScheduler(batch::ReadSubmissions(dir)));
    std::printf("%s", report.Summary().c_str());
    const std::vector<int> again = report.ToResubmit();
    if (args->resubmit && !again.empty()) {
      PrintSubmission(batch::SubmitArray(dir, again, batch::ScriptThrottle(dir.script())));
    }
    ExitWith(
        report.ExitStatus(),
        std::to_string(report.NotDone()) + " item(s) not done (see above)" +
            (args->resubmit && !again.empty() ? "; resubmitted " + batch::ArraySpec(again) : ""));
  });
}

}  // namespace

void RegisterBatchCommands(CLI::App& app) {
  CLI::App* batch =
      app.add_subcommand("batch", "Reconstruct an archive as a Slurm job array (docs/slurm.md)");
  batch->require_subcommand(1);
  RegisterPrepare(batch);
  RegisterSubmit(batch);
  RegisterRun(batch);
  RegisterStatus(batch);
  RegisterCollect(batch);
}

}  // namespace brdfrig::apps
